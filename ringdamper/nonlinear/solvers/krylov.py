"""Linear solves with a lagged factorisation: GMRES on the current Jacobian, preconditioned by the LU
of an earlier one (Knoll & Keyes, *Jacobian-free Newton–Krylov methods*, J. Comput. Phys. 193, 2004,
§3.1: a preconditioner is formed "lagged", at an earlier iterate, and reused while the Krylov
iterations stay few).

Along a continuation the Jacobian of neighbouring points differs by a small change (the contact
pairs whose stick/slip state changes, ω and ξ); the LU of one point then makes GMRES on the next
converge in a few iterations, each a product ``J v`` (:mod:`ringdamper.nonlinear.solvers.jacobian`) and a
triangular solve, far cheaper than forming and factorising ``J``. When GMRES needs more than
``max_iterations`` the Jacobian is formed and factorised after all, and that LU serves the next
points.

Norm: with ``P`` the lagged LU and ``W = diag(1/scale)`` (the unknowns' convergence scales), GMRES
runs on ``W P⁻¹ J x = W P⁻¹ b`` (left preconditioning), so it minimises the scaled estimate of the
error in the unknowns and stops when that is below ``rtol`` times the scaled size of ``P⁻¹ b``.
"""
from __future__ import annotations

import numpy as np
from scipy.sparse.linalg import LinearOperator, gmres

from ringdamper.nonlinear.solvers.jacobian import apply, dense

#: GMRES iterations (one ``J v`` product and one triangular solve each) after which the Jacobian
#: is factorised instead: about the cost of forming and factorising it on the campaign's rings.
MAX_ITERATIONS = 30
#: Relative accuracy of a GMRES solve (scaled 2-norm of the error estimate).
RTOL = 1e-6
#: Smallest system solved with a lagged factorisation: below it the LU costs no more than a few
#: GMRES iterations (n = 400: about 2 ms), and an exact factorisation keeps the Newton's chord
#: steps, and with them the steps of the continuation, those of a fresh Jacobian.
MIN_SIZE = 400


class LaggedSolver:
    """Solver of ``J x = b`` for the Jacobian ``J`` (operator) of one point, preconditioned by
    ``base`` (a :class:`ringdamper.nonlinear.solvers.newton.Factorization` of an earlier Jacobian of the
    same shape); ``weights``: ``1/scale`` of the unknowns. ``factorize(J)`` builds the LU used
    when GMRES does not converge (it then solves every later system directly)."""

    def __init__(self, J, base, weights: np.ndarray, factorize, max_iterations: int = MAX_ITERATIONS,
                 rtol: float = RTOL):
        self.J, self.base, self.weights, self.factorize = J, base, weights, factorize
        self.max_iterations, self.rtol = max_iterations, rtol
        self.exact = None
        n = J.shape[0]
        self._op = LinearOperator((n, n), matvec=self._preconditioned, dtype=float)

    @property
    def factorization(self):
        """The LU this solver stands on: its own once formed, else the lagged one."""
        return self.exact if self.exact is not None else self.base

    def solve(self, b: np.ndarray) -> np.ndarray:
        if self.exact is not None:
            return self.exact.solve(b)
        x0 = self.base.solve(b)
        rhs = self.weights * x0
        if not np.all(np.isfinite(rhs)) or not np.any(rhs):
            return x0
        x, info = gmres(self._op, rhs, x0=x0, rtol=self.rtol, atol=0.0, restart=self.max_iterations,
                        maxiter=1)
        if info == 0 and np.all(np.isfinite(x)):
            return x
        self.exact = self.factorize(dense(self.J))
        return self.exact.solve(b)

    def _preconditioned(self, v: np.ndarray) -> np.ndarray:
        return self.weights * self.base.solve(apply(self.J, v))
