"""Step 2 of the reduction: Mead's cyclic constraint per harmonic on the Craig–Bampton model (Mead 1975).

Harmonic h of the EO travelling wave lives in the nodal diameter of inter-sector phase
sigma_h = ``interblade_phase(h, N, EO)`` (``ringdamper.fem.cyclic``): u_{j+1} = e^{i sigma_h} u_j.
On the right cut this reads node by node u_R = e^{i sigma_h} R_z(2 pi / N) u_L, so the right-face
boundary coordinates of the CB model are eliminated:

    x_cb = T_h x,  x = [physical, left, eta],  rows of ``right`` in T_h = e^{i sigma_h} R (left partners),

and K_h = T_h^H K_cb T_h, M_h = T_h^H M_cb T_h are complex Hermitian (real for sigma = 0, pi).
The interior of the CB model (fixed-interface modes) needs no constraint: with the right face
clamped it is the same for every harmonic.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from .craig_bampton import CraigBampton
from .partition import Partition


@dataclass
class CyclicModel:
    sigma: float
    K: np.ndarray   # Hermitian, order [physical, left, eta]
    M: np.ndarray
    n_physical: int
    n_left: int
    n_fi: int

    @property
    def size(self) -> int:
        return self.K.shape[0]


def rotation_z(angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def mead_transform(cb: CraigBampton, part: Partition, sector_angle: float,
                   sigma: float) -> sp.csr_matrix:
    """T_h (n_cb x n_kept): CB coordinates from [physical, left, eta] for inter-sector phase sigma."""
    nb, n_fi = cb.n_boundary, cb.n_fi
    if not np.array_equal(cb.boundary, part.boundary):
        raise ValueError("the CB model must retain partition.boundary in its order")
    position = np.full(part.n_dofs, -1)
    position[cb.boundary] = np.arange(nb)
    n_keep = len(part.physical) + len(part.left)
    kept_rows = np.concatenate([np.arange(n_keep), nb + np.arange(n_fi)])   # CB coordinate ids
    column = np.full(nb + n_fi, -1)
    column[kept_rows] = np.arange(len(kept_rows))

    phase = np.exp(1j * sigma)
    if abs(phase.imag) < 1e-14:
        phase = phase.real
    rot = rotation_z(sector_angle)
    rows, cols, vals = [kept_rows], [np.arange(len(kept_rows))], [np.ones(len(kept_rows))]
    for a in range(3):
        for b in range(3):
            if rot[a, b] == 0.0:
                continue
            r = position[3 * part.right_nodes + a]
            c = column[position[3 * part.left_nodes + b]]
            if np.any(r < 0) or np.any(c < 0):
                raise ValueError("a cyclic-face DoF is missing from the CB boundary")
            rows.append(r)
            cols.append(c)
            vals.append(np.full(len(r), phase * rot[a, b]))
    vals = np.concatenate(vals)
    return sp.csr_matrix((vals, (np.concatenate(rows), np.concatenate(cols))),
                         shape=(nb + n_fi, len(kept_rows)))


def _congruence(T: sp.csr_matrix, A: np.ndarray) -> np.ndarray:
    """T^H A T for a dense symmetric A and a sparse T, made exactly Hermitian."""
    AT = (T.T @ A).T            # A T (A symmetric)
    out = np.asarray(T.conj().T @ AT)
    return 0.5 * (out + out.conj().T)


def mead(cb: CraigBampton, part: Partition, sector_angle: float, sigma: float) -> CyclicModel:
    """(K_h, M_h) of the CB model under the cyclic constraint of phase ``sigma``."""
    T = mead_transform(cb, part, sector_angle, sigma)
    return CyclicModel(sigma=sigma, K=_congruence(T, cb.K), M=_congruence(T, cb.M),
                       n_physical=len(part.physical), n_left=len(part.left), n_fi=cb.n_fi)
