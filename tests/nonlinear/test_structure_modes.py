"""Modes of a structure (:mod:`ringdamper.nonlinear.harmonic_balance.structure`): a pencil that is diagonal (a structure
given in its own modes, as the campaign's reduced.nc) is solved as such, identical to LAPACK's
answer; any other pencil by LAPACK; the stuck modes are computed once per stiffness."""
import numpy as np
import pytest
import scipy.linalg as sla

from ringdamper.nonlinear.harmonic_balance.structure import Structure, _mass_normalised_modes


def test_diagonal_pencil_in_ascending_order_is_lapacks_answer_bit_for_bit():
    w2 = np.sort(np.random.default_rng(0).uniform(1.0, 1e8, 60))
    K, M = np.diag(w2), np.eye(60)
    ours = _mass_normalised_modes(K, M, real=True)
    lapack = sla.eigh(K, M)
    assert np.array_equal(ours[0], lapack[0]) and np.array_equal(ours[1], lapack[1])


def test_diagonal_pencil_in_any_order_and_any_mass_solves_the_eigenproblem():
    rng = np.random.default_rng(1)
    k, m = rng.uniform(1.0, 1e6, 40), rng.uniform(0.5, 2.0, 40)
    w2, Phi = _mass_normalised_modes(np.diag(k), np.diag(m), real=True)
    assert np.all(np.diff(w2) >= 0)
    np.testing.assert_allclose(w2, np.sort(k / m), rtol=1e-15)
    np.testing.assert_allclose(np.diag(k) @ Phi, np.diag(m) @ Phi * w2, rtol=0, atol=1e-9 * k.max())
    np.testing.assert_allclose(Phi.T @ np.diag(m) @ Phi, np.eye(40), atol=1e-15)


def test_full_pencil_goes_to_lapack():
    rng = np.random.default_rng(2)
    A = rng.standard_normal((30, 30))
    K, M = A @ A.T + 30 * np.eye(30), np.eye(30) + 0.1 * np.ones((30, 30))
    w2, Phi = _mass_normalised_modes(K, M, real=True)
    np.testing.assert_allclose(K @ Phi, M @ Phi * w2, atol=1e-10 * w2.max())
    np.testing.assert_allclose(Phi.T @ M @ Phi, np.eye(30), atol=1e-12)


def test_stuck_modes_are_computed_once_per_stiffness_and_read_only():
    rng = np.random.default_rng(3)
    n, p = 12, 6
    B = rng.standard_normal((p, n))
    st = Structure.real(np.eye(n), np.diag(np.arange(1.0, n + 1) ** 2), B, np.eye(n)[0], np.zeros(n), H=1)
    k = np.full(p, 10.0)
    first = st.stuck_modes(k)
    again = st.stuck_modes(k.copy())
    assert again[0] is first[0] and again[1] is first[1]
    with pytest.raises(ValueError):
        first[1][0, 0] = 1.0
    stiffer = st.stuck_modes(2 * k)
    assert stiffer[0][0] > first[0][0]
    K = np.diag(np.arange(1.0, n + 1) ** 2) + B.T @ (k[:, None] * B)
    np.testing.assert_allclose(first[0] ** 2, sla.eigh(K, eigvals_only=True), rtol=1e-12)
