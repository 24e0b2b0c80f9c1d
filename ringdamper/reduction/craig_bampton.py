"""Step 1 of the reduction: Craig–Bampton on the real sector (Craig & Bampton 1968; paper §2.5.1).

With the free DoFs split into retained (boundary) b and interior i, the interior is represented by
the static constraint modes Psi = -K_ii^{-1} K_ib (one per retained DoF) and the first ``n_fi``
fixed-interface modes K_ii Phi = M_ii Phi Lambda (mass-normalised):

    u_b = u_b,  u_i = Psi u_b + Phi eta,

    K_cb = [[K_bb + K_bi Psi, 0], [0, Lambda]],
    M_cb = [[M_bb + M_bi Psi + Psi^T M_ib + Psi^T M_ii Psi, (M_bi + Psi^T M_ii) Phi], [., I]].

K_ii (positive definite: the boundary and the bore are held) is block diagonal over the connected
blocks of the interior (the ring and the blisk, which only contact couples); each block is factorised
once as P K Pᵀ = L D Lᵀ (``ringdamper.fem.supernodal``), and the same factors give its constraint
modes, all its right-hand sides in one level-3 BLAS block solve, and drive the shift-invert Lanczos
of the fixed-interface modes.
The matrices stay real and symmetric: the cyclic constraint (step 2) comes after, so one
factorisation serves every harmonic. Static condensation is exact: for loads on the retained DoFs,
K_cb reproduces the full model's static response there (tested).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
from scipy.sparse.csgraph import connected_components

from ..fem.linalg import lowest_modes
from ..fem.supernodal import SupernodalLDL
from .hermitian_cb import COLUMN_BLOCK

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
    cpu_s: dict = field(default_factory=dict)  # CPU seconds: constraint_modes, fixed_interface_modes, products

    @property
    def n_boundary(self) -> int:
        return len(self.boundary)

    @property
    def n_fi(self) -> int:
        return len(self.omega2_fixed_interface)

    @property
    def size(self) -> int:
        return self.K.shape[0]


@dataclass
class InteriorBlock:
    """One connected component of the interior (the ring and the blisk are separate bodies without
    contact): its constraint modes Psi[rows, cols], zero outside."""
    rows: np.ndarray          # interior positions of the component
    cols: np.ndarray          # boundary coordinates its stiffness couples to
    factors: SupernodalLDL    # of K_ii[rows, rows]
    psi: np.ndarray           # -K_ii[rows, rows]^-1 K_ib[rows, cols]


def interior_blocks(Kii: sp.csr_matrix, Mii: sp.csr_matrix, Kib: sp.csr_matrix) -> list[InteriorBlock]:
    """The constraint modes per connected component of the interior (of K_ii and M_ii together, so
    both are block diagonal): each is solved only for the boundary coordinates it couples to."""
    n_blocks, label = connected_components(abs(Kii) + abs(Mii), directed=False)
    blocks = []
    for c in range(n_blocks):
        rows = np.flatnonzero(label == c)
        K_rb = Kib[rows]
        cols = np.unique(K_rb.indices)
        factors = SupernodalLDL(Kii[rows][:, rows])
        blocks.append(InteriorBlock(rows=rows, cols=cols, factors=factors, psi=factors.solve(-K_rb[:, cols])))
    return blocks


def _interior_rows(A: sp.csr_matrix, interior: np.ndarray, boundary: np.ndarray):
    """(A_ii, A_ib): the interior rows are sliced once and not kept."""
    A_i = A[interior]
    return A_i[:, interior].tocsr(), A_i[:, boundary]


class _BlockDiagonalSolve:
    """K_ii^-1 x with K_ii block diagonal over the interior blocks (one vector, SuperLU's solve)."""

    def __init__(self, blocks: list[InteriorBlock]):
        self.blocks = blocks

    def solve(self, x: np.ndarray) -> np.ndarray:
        y = np.empty_like(x)
        for b in self.blocks:
            y[b.rows] = b.factors.lu.solve(x[b.rows])
        return y


def _fixed_interface_modes(Kii, Mii, inverse, n_fi):
    n = Kii.shape[0]
    if n_fi == 0:
        return np.zeros(0), np.zeros((n, 0))
    if n_fi > n:
        raise ValueError(f"n_fi = {n_fi} exceeds the {n} interior DoFs")
    if n <= DENSE_EIGEN_LIMIT or n_fi >= n - 1:
        w2, phi = sla.eigh(Kii.toarray(), Mii.toarray(), subset_by_index=(0, n_fi - 1))
        return w2, phi / np.sqrt(np.einsum("ij,ij->j", phi, Mii @ phi))
    return lowest_modes(Kii, Mii, n_fi, shift=0.0, lu=inverse)


def _add_interior_mass(M_bb, M_bf, M_block, b: InteriorBlock, phi_block) -> None:
    """M_bb += Psi^T M_ii Psi and M_bf += Psi^T M_ii Phi on the block's columns, with M_ii Psi formed
    by column blocks of Psi (:data:`~.hermitian_cb.COLUMN_BLOCK` columns), never whole."""
    for start in range(0, len(b.cols), COLUMN_BLOCK):
        cols = slice(start, start + COLUMN_BLOCK)
        mi_psi = M_block @ b.psi[:, cols]
        M_bb[np.ix_(b.cols, b.cols[cols])] += b.psi.T @ mi_psi
        M_bf[b.cols[cols]] += mi_psi.T @ phi_block


def craig_bampton(K: sp.spmatrix, M: sp.spmatrix, boundary, interior, n_fi: int,
                  keep_modes: bool = False) -> CraigBampton:
    """Craig–Bampton model of (K, M) restricted to ``boundary`` U ``interior`` (clamped DoFs absent).

    ``boundary`` order is kept: coordinate j < len(boundary) is the physical DoF boundary[j].
    The products with Psi run per interior block (:func:`interior_blocks`), Psi being zero between
    a block's rows and the boundary coordinates it does not touch.
    """
    boundary, interior = np.asarray(boundary), np.asarray(interior)
    K, M = sp.csr_matrix(K), sp.csr_matrix(M)
    Kii, Kib = _interior_rows(K, interior, boundary)
    Mii, Mib = _interior_rows(M, interior, boundary)
    nb = len(boundary)
    K_bb = K[boundary][:, boundary].toarray()
    M_bb = M[boundary][:, boundary].toarray()

    cpu = [time.process_time()]
    blocks = interior_blocks(Kii, Mii, Kib)
    cpu.append(time.process_time())
    w2, phi = _fixed_interface_modes(Kii, Mii, _BlockDiagonalSolve(blocks), n_fi)
    cpu.append(time.process_time())
    M_bf = Mib.T @ phi                                   # (M_bi + Psi^T M_ii) Phi
    for b in blocks:
        K_bb[np.ix_(b.cols, b.cols)] += Kib[b.rows][:, b.cols].T @ b.psi
        x = Mib[b.rows].T @ b.psi                         # M_bi Psi on the block's columns
        M_bb[:, b.cols] += x
        M_bb[b.cols] += x.T
        _add_interior_mass(M_bb, M_bf, Mii[b.rows][:, b.rows], b, phi[b.rows])

    K_cb = np.zeros((nb + n_fi, nb + n_fi))
    K_cb[:nb, :nb] = K_bb
    K_cb[nb:, nb:] = np.diag(w2)
    M_cb = np.empty_like(K_cb)
    M_cb[:nb, :nb] = M_bb
    M_cb[:nb, nb:] = M_bf
    M_cb[nb:, :nb] = M_bf.T
    M_cb[nb:, nb:] = np.eye(n_fi)
    K_cb = 0.5 * (K_cb + K_cb.T)
    M_cb = 0.5 * (M_cb + M_cb.T)
    psi = None
    if keep_modes:
        psi = np.zeros((len(interior), nb))
        for b in blocks:
            psi[np.ix_(b.rows, b.cols)] = b.psi
    cpu.append(time.process_time())
    return CraigBampton(boundary=boundary, K=K_cb, M=M_cb, omega2_fixed_interface=w2,
                        constraint_modes=psi,
                        fixed_interface_modes=phi if keep_modes else None,
                        interior=interior if keep_modes else None,
                        cpu_s={k: float(t) for k, t in zip(("constraint_modes", "fixed_interface_modes", "products"),
                                                            np.diff(cpu))})


def truncate(cb: CraigBampton, n_fi: int) -> CraigBampton:
    """The CB model with only the first ``n_fi`` fixed-interface modes (identical to recomputing it)."""
    if n_fi > cb.n_fi:
        raise ValueError(f"cannot extend {cb.n_fi} fixed-interface modes to {n_fi}")
    n = cb.n_boundary + n_fi
    return CraigBampton(boundary=cb.boundary, K=cb.K[:n, :n].copy(), M=cb.M[:n, :n].copy(),
                        omega2_fixed_interface=cb.omega2_fixed_interface[:n_fi])
