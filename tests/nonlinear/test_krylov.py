"""Solves with a lagged factorisation (:mod:`ringdamper.nonlinear.solvers.krylov`): GMRES on the current
Jacobian preconditioned by an earlier LU reaches the direct solution to its tolerance, and falls
back to factorising the current Jacobian (then exact to round-off) when a large change of the
Jacobian would need more iterations than allowed; small systems are always factorised."""
import numpy as np
import pytest

from ringdamper.nonlinear.solvers import krylov
from ringdamper.nonlinear.solvers.jacobian import bordered
from ringdamper.nonlinear.solvers.krylov import LaggedSolver
from ringdamper.nonlinear.solvers.newton import Factorization, linear_solver


class Operator:
    """A dense matrix seen only through its products (counted; and formed on demand)."""

    def __init__(self, A):
        self.A, self.shape, self.formed, self.products = A, A.shape, 0, 0

    def matvec(self, v):
        self.products += 1
        return self.A @ v

    def toarray(self, out=None):
        self.formed += 1
        if out is None:
            return self.A.copy()
        out[...] = self.A
        return out


def _systems(n, change, rank, seed=0):
    """An earlier Jacobian ``A0`` and the current one: ``A0`` plus a small full perturbation of
    relative size ``change`` and a rank-``rank`` block of order one (a pair changing state)."""
    rng = np.random.default_rng(seed)
    A0 = np.eye(n) * 4 + rng.standard_normal((n, n)) / np.sqrt(n)
    A1 = A0 + change * rng.standard_normal((n, n)) / np.sqrt(n)
    if rank:
        A1 += rng.standard_normal((n, rank)) @ rng.standard_normal((rank, n)) / np.sqrt(n)
    return A0, A1, rng.standard_normal(n)


def test_gmres_on_a_lagged_lu_reaches_the_direct_solution():
    A0, A1, b = _systems(300, 1e-2, 0)
    J = Operator(A1)
    solver = LaggedSolver(J, Factorization(A0, None, 300), np.ones(300), lambda A: Factorization(A, None, 300))
    x = solver.solve(b)
    exact = np.linalg.solve(A1, b)
    assert np.linalg.norm(x - exact) <= 10 * krylov.RTOL * np.linalg.norm(exact)
    assert solver.exact is None and J.formed == 0              # solved without forming J


def test_a_large_change_falls_back_to_the_factorisation_of_the_current_jacobian():
    A0, A1, b = _systems(300, 1e-2, 60)
    J = Operator(A1)
    solver = LaggedSolver(J, Factorization(A0, None, 300), np.ones(300), lambda A: Factorization(A, None, 300),
                          max_iterations=10)
    x = solver.solve(b)
    assert solver.exact is not None and J.formed == 1
    assert np.allclose(A1 @ x, b, rtol=0, atol=1e-12 * np.linalg.norm(b))
    assert solver.factorization is solver.exact                # later solvers stand on it


@pytest.mark.parametrize("n, lagged", [(krylov.MIN_SIZE - 1, False), (krylov.MIN_SIZE, True)])
def test_only_large_operators_are_solved_with_a_lagged_factorisation(n, lagged):
    A0, A1, b = _systems(n, 1e-3, 0)
    previous = Factorization(A0, None, n)
    solver = linear_solver(Operator(A1), None, n, previous, np.ones(n))
    assert isinstance(solver, LaggedSolver) == lagged
    assert isinstance(linear_solver(A1, None, n, previous, np.ones(n)), Factorization)  # a matrix: its LU


def test_bordered_operator_equals_the_bordered_matrix():
    rng = np.random.default_rng(2)
    A, col, rows = rng.standard_normal((5, 4)), rng.standard_normal((5, 2)), rng.standard_normal((3, 6))
    B = bordered(Operator(A), col, rows)
    v = rng.standard_normal(6)
    assert np.allclose(B.matvec(v), B.toarray() @ v, rtol=1e-14)
    assert np.array_equal(B.toarray(), bordered(A, col, rows))


def test_linear_solver_gives_the_accuracy_asked_with_fewer_products():
    """``linear_solver(…, rtol)`` (the forced responses' tangents: 1e-4) solves to that accuracy and
    no further: fewer ``J v`` products than at the default 1e-6, an error above the default's."""
    A0, A1, b = _systems(krylov.MIN_SIZE, 5e-2, 0)
    exact = np.linalg.solve(A1, b)
    base = Factorization(A0, None, A0.shape[0])
    errors, products = {}, {}
    for rtol in (krylov.RTOL, 1e-4):
        J = Operator(A1)
        solver = linear_solver(J, None, A0.shape[0], base, np.ones(A0.shape[0]), rtol=rtol)
        x = solver.solve(b)
        assert solver.exact is None
        errors[rtol], products[rtol] = np.linalg.norm(x - exact) / np.linalg.norm(exact), J.products
        assert errors[rtol] <= 10 * rtol
    assert products[1e-4] < products[krylov.RTOL] and errors[1e-4] > errors[krylov.RTOL]
