"""Step 1 of the reduction: Craig–Bampton on the real sector (Craig & Bampton 1968; paper §2.5.1).

With the free DoFs split into retained (boundary) b and interior i, the interior is represented by
the static constraint modes Psi = -K_ii^{-1} K_ib (one per retained DoF) and the first ``n_fi``
fixed-interface modes K_ii Phi = M_ii Phi Lambda (mass-normalised):

    u_b = u_b,  u_i = Psi u_b + Phi eta,

    K_cb = [[K_bb + K_bi Psi, 0], [0, Lambda]],
    M_cb = [[M_bb + M_bi Psi + Psi^T M_ib + Psi^T M_ii Psi, (M_bi + Psi^T M_ii) Phi], [., I]].

K_ii (positive definite: the boundary and the bore are held) is factorised once as P K_ii Pᵀ = L D Lᵀ
(``ringdamper.fem.supernodal``); the same factors give the constraint modes, all right-hand sides
in one level-3 BLAS block solve, and drive the shift-invert Lanczos of the fixed-interface modes.
The matrices stay real and symmetric: the cyclic constraint (step 2) comes after, so one
factorisation serves every harmonic. Static condensation is exact: for loads on the retained DoFs,
K_cb reproduces the full model's static response there (tested).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp

from ..fem.linalg import lowest_modes
from ..fem.supernodal import SupernodalLDL

DENSE_EIGEN_LIMIT = 600  # interior sizes below this use a dense eigensolver for the fixed-interface modes


@dataclass
class CraigBampton:
    boundary: np.ndarray          # global DoFs of the first len(boundary) coordinates
    K: np.ndarray                 # (n_b + n_fi)^2, real symmetric
    M: np.ndarray
    omega2_fixed_interface: np.ndarray  # (n_fi,) rad^2/s^2
    constraint_modes: np.ndarray | None = None  # Psi (n_i x n_b), kept on request (tests, recovery)
    fixed_interface_modes: np.ndarray | None = None  # Phi (n_i x n_fi), kept on request
    interior: np.ndarray | None = None

    @property
    def n_boundary(self) -> int:
        return len(self.boundary)

    @property
    def n_fi(self) -> int:
        return len(self.omega2_fixed_interface)

    @property
    def size(self) -> int:
        return self.K.shape[0]


def _fixed_interface_modes(Kii, Mii, lu, n_fi):
    n = Kii.shape[0]
    if n_fi == 0:
        return np.zeros(0), np.zeros((n, 0))
    if n_fi > n:
        raise ValueError(f"n_fi = {n_fi} exceeds the {n} interior DoFs")
    if n <= DENSE_EIGEN_LIMIT or n_fi >= n - 1:
        w2, phi = sla.eigh(Kii.toarray(), Mii.toarray(), subset_by_index=(0, n_fi - 1))
        return w2, phi / np.sqrt(np.einsum("ij,ij->j", phi, Mii @ phi))
    return lowest_modes(Kii, Mii, n_fi, shift=0.0, lu=lu)


def craig_bampton(K: sp.spmatrix, M: sp.spmatrix, boundary, interior, n_fi: int,
                  keep_modes: bool = False) -> CraigBampton:
    """Craig–Bampton model of (K, M) restricted to ``boundary`` U ``interior`` (clamped DoFs absent).

    ``boundary`` order is kept: coordinate j < len(boundary) is the physical DoF boundary[j].
    """
    boundary, interior = np.asarray(boundary), np.asarray(interior)
    K, M = sp.csr_matrix(K), sp.csr_matrix(M)
    K_i, M_i = K[interior], M[interior]
    Kii, Kib = K_i[:, interior].tocsc(), K_i[:, boundary]
    Mii, Mib = M_i[:, interior].tocsr(), M_i[:, boundary]
    Kbb = K[boundary][:, boundary].toarray()
    Mbb = M[boundary][:, boundary].toarray()

    factors = SupernodalLDL(Kii)
    psi = -factors.solve(Kib.toarray())
    w2, phi = _fixed_interface_modes(Kii, Mii, factors.lu, n_fi)

    nb = len(boundary)
    K_cb = np.zeros((nb + n_fi, nb + n_fi))
    K_cb[:nb, :nb] = Kbb + Kib.T @ psi
    K_cb[nb:, nb:] = np.diag(w2)
    mi_psi = Mii @ psi
    x = Mib.T @ psi
    M_cb = np.empty_like(K_cb)
    M_cb[:nb, :nb] = Mbb + x + x.T + psi.T @ mi_psi
    M_cb[:nb, nb:] = Mib.T @ phi + mi_psi.T @ phi
    M_cb[nb:, :nb] = M_cb[:nb, nb:].T
    M_cb[nb:, nb:] = np.eye(n_fi)
    K_cb = 0.5 * (K_cb + K_cb.T)
    M_cb = 0.5 * (M_cb + M_cb.T)
    return CraigBampton(boundary=boundary, K=K_cb, M=M_cb, omega2_fixed_interface=w2,
                        constraint_modes=psi if keep_modes else None,
                        fixed_interface_modes=phi if keep_modes else None,
                        interior=interior if keep_modes else None)


def truncate(cb: CraigBampton, n_fi: int) -> CraigBampton:
    """The CB model with only the first ``n_fi`` fixed-interface modes (identical to recomputing it)."""
    if n_fi > cb.n_fi:
        raise ValueError(f"cannot extend {cb.n_fi} fixed-interface modes to {n_fi}")
    n = cb.n_boundary + n_fi
    return CraigBampton(boundary=cb.boundary, K=cb.K[:n, :n].copy(), M=cb.M[:n, :n].copy(),
                        omega2_fixed_interface=cb.omega2_fixed_interface[:n_fi])
