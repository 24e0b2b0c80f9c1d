"""Newton–Raphson on dense Jacobians with exact elimination of trivial unknowns.

The condensed HBM Jacobian (:mod:`ringdamper.hbm.condensed`) has unit-vector columns for the
contact coordinates of pairs whose contact Jacobian vanishes (open during the whole period, or
decoupled): such an unknown appears only in its own row (identity) and possibly in the extra
rows appended by the problem (normalisation, phase, arc-length). :class:`Factorization`
eliminates them exactly before the LU factorisation, so the dense solve only involves the
active pairs.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable

import numpy as np
import scipy.linalg as sla


class Factorization:
    """LU of ``J`` after eliminating the trivial unknowns ``T`` (columns ``e_i`` in the first
    ``n_core`` rows): ``x_T = b_T − J[T, N] x_N`` and the Schur system on the other unknowns."""

    def __init__(self, J: np.ndarray, trivial: np.ndarray | None, n_core: int):
        n = J.shape[0]
        T = np.zeros(n, bool) if trivial is None else np.r_[trivial, np.zeros(n - trivial.size, bool)]
        self.T, self.N = np.flatnonzero(T), np.flatnonzero(~T)
        extra = self.N[self.N >= n_core]                     # rows that may touch T columns
        self.JTN = J[np.ix_(self.T, self.N)]
        self.JXT = J[np.ix_(extra, self.T)]
        self.extra_pos = np.searchsorted(self.N, extra)
        A = J[np.ix_(self.N, self.N)]
        if self.T.size and extra.size:
            A[self.extra_pos] -= self.JXT @ self.JTN
        self.lu = sla.lu_factor(A, check_finite=False)

    def solve(self, b: np.ndarray) -> np.ndarray:
        bN = b[self.N].copy()
        if self.T.size and self.extra_pos.size:
            bN[self.extra_pos] -= self.JXT @ b[self.T]
        x = np.empty_like(b)
        x[self.N] = sla.lu_solve(self.lu, bN, check_finite=False)
        x[self.T] = b[self.T] - self.JTN @ x[self.N]
        return x


@dataclass
class NewtonResult:
    z: np.ndarray
    converged: bool
    iterations: int
    payload: Any                      # the problem's evaluation at ``z``
    factorization: Factorization | None
    reason: str = ""


def newton(fun: Callable, z0: np.ndarray, scale: Callable[[np.ndarray], np.ndarray],
           tol: float = 1e-10, max_iter: int = 20, lambda_min: float = 1.0 / 256) -> NewtonResult:
    """Damped Newton for ``r(z) = 0``; ``fun(z, jacobian) -> (r, J, trivial, n_core, payload)``
    (``J`` may be None when ``jacobian`` is false).

    Converged when the Newton step computed at ``z`` satisfies ``max |δz| / scale(z) ≤ tol``;
    ``z`` (with its evaluation and factorisation) is returned, so outputs and tangents are
    consistent with it. Damping (Deuflhard's natural monotonicity test, affine invariant): a step
    ``λ δz`` is accepted when the simplified correction ``J(z)⁻¹ r(z + λδz)`` is shorter than
    ``(1 − λ/4) |δz|``, else λ is halved down to ``lambda_min``. This breaks the cycles that plain
    Newton falls into on the piecewise-linear AFT residual near stick–slip transitions."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        return _damped_newton(fun, np.array(z0, float), scale, tol, max_iter, lambda_min)


def _damped_newton(fun, z, scale, tol, max_iter, lambda_min):
    ev = fun(z, True)
    fac = None
    for it in range(max_iter + 1):
        r, J, trivial, n_core, payload = ev
        if not (np.all(np.isfinite(r)) and np.all(np.isfinite(J))):
            return NewtonResult(z, False, it, payload, None, "non-finite residual or Jacobian")
        fac = Factorization(J, trivial, n_core)
        dz = fac.solve(-r)
        if not np.all(np.isfinite(dz)):
            return NewtonResult(z, False, it, payload, fac, "singular Jacobian")
        sc = scale(z)
        step = np.max(np.abs(dz) / sc)
        if step <= tol:
            return NewtonResult(z, True, it, payload, fac)
        if it == max_iter:
            break
        lam = 1.0
        while True:
            rt = fun(z + lam * dz, False)[0]
            bar = fac.solve(-rt) if np.all(np.isfinite(rt)) else np.full(z.size, np.inf)
            if np.max(np.abs(bar) / sc) <= (1.0 - lam / 4) * step or lam <= lambda_min:
                break
            lam *= 0.5
        z = z + lam * dz
        ev = fun(z, True)
    return NewtonResult(z, False, max_iter, payload, fac, f"no convergence in {max_iter} iterations")
