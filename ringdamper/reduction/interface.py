"""Step 3 of the reduction: the remaining cyclic-face DoFs by partial interface modes (Tran 2009).

After Mead's constraint the coordinates are x = [p, l, eta]: p the physical contact and response
DoFs, l the left-face DoFs (the right face is gone), eta the fixed-interface modal coordinates. The
face DoFs l are reduced by a second Craig–Bampton step on the interface itself, p acting as its
boundary:

    l = S p + Phi_if r,   S = -K_ll^{-1} K_lp,   K_ll Phi_if = M_ll Phi_if Lambda_if (lowest n_if),

with K_ll, M_ll the face blocks of the harmonic's Hermitian matrices (the CB boundary partition,
i.e. the Guyan face stiffness and mass with the physical DoFs held). The contact, response and
fixed-interface coordinates are untouched. The static lift S keeps static condensation exact (K_ml
is zero for the CB modes) and keeps the ring's ND-0 rigid motions exact whatever n_if is; the modes
Phi_if (computed once per harmonic, Hermitian) bring the face inertia.

Final coordinates y = [p, r, eta] (sizes n_p, n_if, n_fi).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla

from .cyclic import CyclicModel


@dataclass
class InterfaceReduced:
    sigma: float
    K: np.ndarray   # Hermitian, order [physical, interface modes, fixed-interface modes]
    M: np.ndarray
    n_physical: int
    n_if: int
    n_fi: int
    omega2_interface: np.ndarray  # (n_if,) eigenvalues of the face block

    @property
    def size(self) -> int:
        return self.K.shape[0]


def interface_transform(cm: CyclicModel, n_if: int) -> tuple[np.ndarray, np.ndarray]:
    """(T, Lambda_if): x = T y with y = [p, r, eta]; T is (n_p + n_l + n_fi) x (n_p + n_if + n_fi)."""
    n_p, n_l, n_fi = cm.n_physical, cm.n_left, cm.n_fi
    if not 0 <= n_if <= n_l:
        raise ValueError(f"n_if = {n_if} outside [0, {n_l}] (face DoFs)")
    p, f = slice(0, n_p), slice(n_p, n_p + n_l)
    K_ll, M_ll, K_lp = cm.K[f, f], cm.M[f, f], cm.K[f, p]
    S = -sla.solve(K_ll, K_lp, assume_a="her")
    if n_if:
        w2, phi = sla.eigh(K_ll, M_ll, subset_by_index=(0, n_if - 1))
    else:
        w2, phi = np.zeros(0), np.zeros((n_l, 0), dtype=K_ll.dtype)
    T = np.zeros((n_p + n_l + n_fi, n_p + n_if + n_fi), dtype=np.result_type(S, phi))
    T[p, :n_p] = np.eye(n_p)
    T[f, :n_p] = S
    T[f, n_p:n_p + n_if] = phi
    T[n_p + n_l:, n_p + n_if:] = np.eye(n_fi)
    return T, w2


def reduce_interface(cm: CyclicModel, n_if: int) -> InterfaceReduced:
    T, w2 = interface_transform(cm, n_if)
    K = T.conj().T @ cm.K @ T
    M = T.conj().T @ cm.M @ T
    return InterfaceReduced(sigma=cm.sigma, K=0.5 * (K + K.conj().T), M=0.5 * (M + M.conj().T),
                            n_physical=cm.n_physical, n_if=n_if, n_fi=cm.n_fi,
                            omega2_interface=w2)
