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


def face_basis(cm: CyclicModel, n_if: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(S, Phi_if, Lambda_if): the static lift of the face DoFs and their lowest ``n_if`` modes."""
    n_p, n_l = cm.n_physical, cm.n_left
    if not 0 <= n_if <= n_l:
        raise ValueError(f"n_if = {n_if} outside [0, {n_l}] (face DoFs)")
    p, f = slice(0, n_p), slice(n_p, n_p + n_l)
    K_ll, M_ll, K_lp = cm.K[f, f], cm.M[f, f], cm.K[f, p]
    S = -sla.solve(K_ll, K_lp, assume_a="pos")   # K_ll: face stiffness with p held, definite
    if n_if:
        w2, phi = sla.eigh(K_ll, M_ll, subset_by_index=(0, n_if - 1))
    else:
        w2, phi = np.zeros(0), np.zeros((n_l, 0), dtype=K_ll.dtype)
    return S, phi, w2


def interface_transform(cm: CyclicModel, S: np.ndarray, phi: np.ndarray) -> np.ndarray:
    """T with x = T y, y = [p, r, eta]: (n_p + n_l + n_fi) x (n_p + n_if + n_fi)."""
    n_p, n_l, n_fi, n_if = cm.n_physical, cm.n_left, cm.n_fi, phi.shape[1]
    p, f = slice(0, n_p), slice(n_p, n_p + n_l)
    T = np.zeros((n_p + n_l + n_fi, n_p + n_if + n_fi), dtype=np.result_type(S, phi))
    T[p, :n_p] = np.eye(n_p)
    T[f, :n_p] = S
    T[f, n_p:n_p + n_if] = phi
    T[n_p + n_l:, n_p + n_if:] = np.eye(n_fi)
    return T


def project_stiffness(K: np.ndarray, S: np.ndarray, phi: np.ndarray, w2: np.ndarray,
                      n_p: int, n_l: int) -> np.ndarray:
    """``Tᴴ K T`` in closed form, made exactly Hermitian: with K_ll S = -K_lp and
    Phi_ifᴴ K_ll Phi_if = Lambda_if (mass-normalised face modes) the [p, r] block is

        [[K_pp + K_pl S, 0], [0, Lambda_if]],

    equal to :func:`project` up to round-off; the eta rows and columns are those of
    :func:`project` (``Wᴴ K_l,eta`` plus ``K_p,eta`` on the p rows, ``K_eta,eta``)."""
    p, f, eta = slice(0, n_p), slice(n_p, n_p + n_l), slice(n_p + n_l, None)
    n_if = len(w2)
    n_pr = n_p + n_if
    out = np.zeros((n_pr + K.shape[0] - n_p - n_l,) * 2, dtype=np.result_type(K, S, phi))
    out[:n_p, :n_p] = K[p, p] + K[p, f] @ S
    out[n_p:n_pr, n_p:n_pr] = np.diag(w2)
    out[:n_p, n_pr:] = K[p, eta] + S.conj().T @ K[f, eta]
    out[n_p:n_pr, n_pr:] = phi.conj().T @ K[f, eta]
    out[n_pr:, n_pr:] = K[eta, eta]
    out[n_pr:, :n_pr] = out[:n_pr, n_pr:].conj().T
    return 0.5 * (out + out.conj().T)


def project(A: np.ndarray, T: np.ndarray, n_p: int, n_l: int) -> np.ndarray:
    """``Tᴴ A T`` for the ``T`` of :func:`interface_transform`, made exactly Hermitian, by blocks:
    only the face rows ``W = T[l, :n_p + n_if] = [S, Phi_if]`` of ``T`` are not identity or zero,
    so ``A T = A[:, l] W + A[:, p]`` on the [p, r] columns and ``A[:, eta]`` on the others, and
    ``Tᴴ (A T) = Wᴴ (A T)[l] + (A T)[p]`` on the [p, r] rows (a third of the dense product's
    flops)."""
    p, f, eta = slice(0, n_p), slice(n_p, n_p + n_l), slice(n_p + n_l, None)
    n_pr = T.shape[1] - (A.shape[0] - n_p - n_l)
    W = T[f, :n_pr]
    AT = np.empty((A.shape[0], T.shape[1]), dtype=np.result_type(A, T))
    AT[:, :n_pr] = A[:, f] @ W
    AT[:, :n_p] += A[:, p]
    AT[:, n_pr:] = A[:, eta]
    out = np.empty((T.shape[1], T.shape[1]), dtype=AT.dtype)
    out[:n_pr] = W.conj().T @ AT[f]
    out[:n_p] += AT[p]
    out[n_pr:] = AT[eta]
    return 0.5 * (out + out.conj().T)


def reduce_interface(cm: CyclicModel, n_if: int) -> InterfaceReduced:
    S, phi, w2 = face_basis(cm, n_if)
    K = project_stiffness(cm.K, S, phi, w2, cm.n_physical, cm.n_left)
    M = project(cm.M, interface_transform(cm, S, phi), cm.n_physical, cm.n_left)
    return InterfaceReduced(sigma=cm.sigma, K=K, M=M,
                            n_physical=cm.n_physical, n_if=n_if, n_fi=cm.n_fi,
                            omega2_interface=w2)
