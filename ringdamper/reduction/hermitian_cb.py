"""Craig–Bampton of a sparse Hermitian pair, cyclically projected already (Craig & Bampton 1968).

With the coordinates split into retained b and interior i, K_ii (Hermitian positive definite)
factorised once (``fem.linalg.factorize``):

    Psi = -K_ii^-1 K_ib,   K_ii Phi = M_ii Phi Lambda (lowest n, Phi^H M_ii Phi = I),

    K_cb = [[K_bb + K_bi Psi, 0], [0, Lambda]],
    M_cb = [[M_bb + M_bi Psi + Psi^H M_ib + Psi^H M_ii Psi, (M_bi + Psi^H M_ii) Phi], [., I]],

and a load f condenses to f_b + Psi^H f_i (Guyan; exact for the static response at b). Unlike
``craig_bampton`` (the real sector, before Mead's constraint) the matrices may be complex: the
substructured chain projects each harmonic cyclically first, so nothing dense is formed over the
cyclic faces. M_ii Psi is formed by column blocks of Psi, never whole.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ..fem.linalg import factorize, lowest_hermitian_modes, lowest_modes

#: Columns of Psi per block of the product M_ii Psi.
COLUMN_BLOCK = 256


@dataclass
class Condensed:
    K: np.ndarray            # (n_b + n_modes)^2 Hermitian
    M: np.ndarray | None     # same, None for a static (Guyan) condensation
    f: np.ndarray | None     # (n_b,) condensed load, None without a load
    omega2: np.ndarray       # (n_modes,) rad^2 s^-2 of the fixed-interface modes


def _sandwich(psi: np.ndarray, Mii: sp.csr_matrix) -> np.ndarray:
    """Psi^H M_ii Psi by column blocks of Psi (one block of M_ii Psi held at a time)."""
    out = np.empty((psi.shape[1],) * 2, dtype=psi.dtype)
    for start in range(0, psi.shape[1], COLUMN_BLOCK):
        cols = slice(start, start + COLUMN_BLOCK)
        out[:, cols] = psi.conj().T @ (Mii @ psi[:, cols])
    return out


def _modes(Kii, Mii, n_modes: int, factors):
    """The lowest ``n_modes`` of the interior, mass-normalised (real or complex Hermitian)."""
    if n_modes == 0:
        return np.zeros(0), np.zeros((Kii.shape[0], 0), dtype=Kii.dtype)
    if np.iscomplexobj(Kii):
        return lowest_hermitian_modes(Kii, Mii, n_modes, factors)
    return lowest_modes(Kii, Mii, n_modes, 0.0, lu=factors)


def _hermitian(A: np.ndarray) -> np.ndarray:
    return 0.5 * (A + A.conj().T)


def condense(K: sp.spmatrix, M: sp.spmatrix | None, boundary, interior, n_modes: int = 0,
             f: np.ndarray | None = None) -> Condensed:
    """The Craig–Bampton model of (K, M) on ``boundary`` (positions, order kept) with ``n_modes``
    fixed-interface modes of ``interior``; M None gives the static condensation only."""
    boundary, interior = np.asarray(boundary), np.asarray(interior)
    if M is None and n_modes:
        raise ValueError("fixed-interface modes need the mass matrix M")
    if not 0 <= n_modes < len(interior):
        raise ValueError(f"n_modes = {n_modes} outside [0, {len(interior)}) (interior DoFs)")
    K = sp.csr_matrix(K)
    K_i = K[interior]
    Kii, Kib = K_i[:, interior].tocsc(), K_i[:, boundary]
    factors = factorize(Kii, definite=True)
    psi = factors.solve(-Kib.toarray())
    nb = len(boundary)
    K_cb = np.zeros((nb + n_modes,) * 2, dtype=psi.dtype)
    K_cb[:nb, :nb] = K[boundary][:, boundary].toarray() + Kib.conj().T @ psi
    f_b = None if f is None else f[boundary] + psi.conj().T @ f[interior]
    if M is None:
        return Condensed(K=_hermitian(K_cb), M=None, f=f_b, omega2=np.zeros(0))
    M = sp.csr_matrix(M)
    M_i = M[interior]
    Mii, Mib = M_i[:, interior].tocsr(), M_i[:, boundary]
    w2, phi = _modes(Kii, Mii, n_modes, factors)
    K_cb[nb:, nb:] = np.diag(w2)
    M_bi_psi = Mib.conj().T @ psi
    M_cb = np.zeros_like(K_cb)
    M_cb[:nb, :nb] = (M[boundary][:, boundary].toarray() + M_bi_psi + M_bi_psi.conj().T
                      + _sandwich(psi, Mii))
    M_cb[:nb, nb:] = Mib.conj().T @ phi + psi.conj().T @ (Mii @ phi)
    M_cb[nb:, :nb] = M_cb[:nb, nb:].conj().T
    M_cb[nb:, nb:] = np.eye(n_modes)
    return Condensed(K=_hermitian(K_cb), M=_hermitian(M_cb), f=f_b, omega2=w2)
