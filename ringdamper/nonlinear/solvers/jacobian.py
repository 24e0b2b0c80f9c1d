"""Jacobians given as matrices or as operators, their bordering, and the evaluation a problem returns.

A problem's ``fun(z, jacobian)`` (:func:`ringdamper.nonlinear.solvers.newton.newton`) returns an
:class:`Evaluation` (residual, Jacobian, trivial unknowns, core size, the problem's own payload). It
may give its Jacobian as a dense array or as an operator with ``shape``, ``matvec(v)`` (the product ``J v``, without
forming ``J``) and ``toarray(out=None)`` (``J`` formed on demand, into ``out`` if given). An
operator lets the Newton solve with a lagged factorisation as preconditioner
(:class:`ringdamper.nonlinear.solvers.krylov.LaggedSolver`) and form ``J`` only when that no longer converges.
The continuation borders Jacobians with extra columns (``∂r/∂s``) and rows (arc-length hyperplane,
amplitude and phase conditions): :func:`bordered` does that for both kinds, and
:meth:`Evaluation.extended` for an evaluation (its residual and Jacobian together).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np


def is_operator(J) -> bool:
    """True for a Jacobian given as an operator (not a dense array)."""
    return J is not None and not isinstance(J, np.ndarray)


def dense(J) -> np.ndarray:
    """The Jacobian as a dense array: for an operator a new one in Fortran order, which LAPACK's LU
    factorises in place when the caller lets it overwrite the matrix (a C-ordered one is copied
    first: 17 MB at n = 1480); ``J`` itself for an array."""
    return J.toarray() if is_operator(J) else J


def fill(J, out: np.ndarray) -> None:
    """Write the Jacobian into ``out`` (a view of a larger matrix, so bordering copies nothing)."""
    if is_operator(J):
        J.toarray(out=out)
    else:
        out[...] = J


def apply(J, v: np.ndarray) -> np.ndarray:
    """The product ``J v``."""
    return J.matvec(v) if is_operator(J) else J @ v


class Bordered:
    """``[[A, C], [R]]``: the operator ``A`` (m × n) with columns ``C`` (m × k) on its right and
    rows ``R`` (l × (n + k)) below."""

    def __init__(self, A, columns: np.ndarray, rows: np.ndarray):
        self.A, self.columns, self.rows = A, columns, rows
        m, n = A.shape
        self.shape = (m + rows.shape[0], n + columns.shape[1])

    def matvec(self, v: np.ndarray) -> np.ndarray:
        n = self.A.shape[1]
        return np.concatenate((apply(self.A, v[:n]) + self.columns @ v[n:], self.rows @ v))

    def reduced_solver(self, full_order: int, outer=None):
        """The solver its innermost operator offers for the whole bordered system (``reduced_solver``,
        e.g. :meth:`ringdamper.nonlinear.harmonic_balance.condensed.CoreJacobian.reduced_solver`), or None."""
        inner = getattr(self.A, "reduced_solver", None)
        return None if inner is None else inner(full_order, self if outer is None else outer)

    def toarray(self, out: np.ndarray | None = None) -> np.ndarray:
        m, n = self.A.shape
        out = np.empty(self.shape, order="F") if out is None else out
        fill(self.A, out[:m, :n])
        out[:m, n:] = self.columns
        out[m:] = self.rows
        return out


def bordered(J, columns=None, rows=None):
    """``J`` with ``columns`` (m × k, or a vector for k = 1) appended on its right and ``rows``
    (l × (n + k), or a vector for l = 1) below, of the same kind as ``J`` (array or operator)."""
    m, n = J.shape
    columns = np.zeros((m, 0)) if columns is None else np.asarray(columns, float).reshape(m, -1)
    rows = np.zeros((0, n + columns.shape[1])) if rows is None else np.atleast_2d(np.asarray(rows, float))
    if is_operator(J):
        return Bordered(J, columns, rows)
    return np.vstack([np.hstack([J, columns]), rows])


@dataclass(frozen=True)
class Evaluation:
    """One evaluation of a system ``r(z) = 0`` for :func:`ringdamper.nonlinear.solvers.newton.newton` and the
    continuation drivers: residual ``r``; Jacobian ``J`` (array or operator; None when not requested);
    ``trivial``, the unknowns whose columns are unit vectors in the first ``n_core`` rows (eliminated
    exactly by :class:`ringdamper.nonlinear.solvers.newton.Factorization`; None: none); ``payload``, the
    problem's own evaluation (e.g. a :class:`ringdamper.nonlinear.harmonic_balance.condensed.CoreEval`), which the
    solvers hand back with the solution."""

    r: np.ndarray
    J: Any
    trivial: np.ndarray | None
    n_core: int
    payload: Any

    def extended(self, equations=(), columns=None, rows=None) -> "Evaluation":
        """The system with the residuals ``equations`` appended, its Jacobian bordered by ``columns`` on
        the right and ``rows`` below (:func:`bordered`; still None where it was not computed)."""
        J = None if self.J is None else bordered(self.J, columns, rows)
        return Evaluation(np.append(self.r, equations), J, self.trivial, self.n_core, self.payload)
