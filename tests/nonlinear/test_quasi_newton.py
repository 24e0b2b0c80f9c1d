"""Quasi-Newton steps on a factorised Jacobian (:class:`QuasiNewtonSteps`, Deuflhard's QNERR).

* Oracle: each correction the recursion returns is ``−J_{k+1}⁻¹ F(x_{k+1})`` for the good Broyden
  matrices formed explicitly, ``J_{k+1} = J_k + F(x_{k+1}) Δx_kᵀ W / (Δx_kᵀ W Δx_k)`` (1e-10
  relative), in the weighted inner product the recursion uses.
* On a smooth system from a Jacobian lagged at another point, where the chord steps contract
  linearly, the quasi-Newton run reaches the tolerance on that one factorisation in fewer steps
  (superlinear), and both runs meet at the root within the tolerance.
* Off by default: ``newton`` without ``quasi_newton`` takes exactly its chord steps."""
import numpy as np

from ringdamper.nonlinear.solvers.jacobian import Evaluation
from ringdamper.nonlinear.solvers.newton import CHORD, Factorization, QuasiNewtonSteps, newton

RNG = np.random.default_rng(7)
N = 6
A = np.eye(N) * 4.0 + RNG.normal(scale=0.5, size=(N, N))
B = RNG.normal(size=N)


def system(z, jacobian):
    """``F(z) = A z + 0.3 sin z − b`` and its Jacobian ``A + 0.3 diag(cos z)``."""
    J = A + 0.3 * np.diag(np.cos(z)) if jacobian else None
    return Evaluation(A @ z + 0.3 * np.sin(z) - B, J, None, N, None)


def test_corrections_are_those_of_the_explicit_broyden_matrices():
    weights = RNG.uniform(0.5, 2.0, N)
    W = np.diag(weights)
    x = RNG.normal(size=N)
    J0 = J = system(x + 0.4, True).J                             # lagged: taken elsewhere
    steps = QuasiNewtonSteps(weights)
    dx = -np.linalg.solve(J0, system(x, False).r)               # J₀'s own first step
    for _ in range(4):
        x_next = x + dx
        F_next = system(x_next, False).r
        got, _ = steps.correction(-np.linalg.solve(J0, F_next), dx)
        J = J + np.outer(F_next, dx @ W) / (dx @ W @ dx)         # good Broyden, weighted
        want = -np.linalg.solve(J, F_next)
        np.testing.assert_allclose(got, want, rtol=1e-10, atol=1e-14 * np.abs(want).max())
        steps.take(dx)
        x, dx = x_next, got


def test_quasi_newton_steps_converge_faster_than_chord_steps_on_a_lagged_jacobian():
    z0 = np.zeros(N)
    lagged = Factorization(system(z0 + 0.8, True).J, None, N)
    tol = 1e-12
    chord = newton(system, z0, np.ones_like, tol, 20, factorization=lagged,
                   theta_max=0.9, chord_budget=200)
    quasi = newton(system, z0, np.ones_like, tol, 20, factorization=lagged, quasi_newton=True,
                   theta_max=0.9, chord_budget=200)
    assert chord.converged and quasi.converged
    assert chord.jacobians == quasi.jacobians == 0                # all steps on the lagged LU
    assert quasi.iterations < chord.iterations
    np.testing.assert_allclose(quasi.z, chord.z, rtol=0, atol=2 * tol)
    assert np.max(np.abs(system(quasi.z, False).r)) < 1e-10


def test_without_the_switch_newton_takes_its_chord_steps():
    z0 = np.zeros(N)
    lagged = Factorization(system(z0 + 0.8, True).J, None, N)
    default = newton(system, z0, np.ones_like, 1e-12, 20, factorization=lagged)
    chord = newton(system, z0, np.ones_like, 1e-12, 20, factorization=lagged,
                   theta_max=CHORD.theta_max, chord_budget=CHORD.chord_budget)
    assert default.iterations == chord.iterations and default.jacobians == chord.jacobians
    np.testing.assert_array_equal(default.z, chord.z)
