"""Condition number of the Newton Jacobian at the converged points (ringdamper.nonlinear.indicators.conditioning):
the equilibrated 1-norm estimate against numpy's exact value, its invariance to the scalings the
equilibration removes, the equilibrated LU's solves, and on the coarse ring's backbone the stuck points'
shared value and the estimates the continuation keeps."""
import numpy as np
import pytest
from scipy.linalg import LinAlgWarning

from ringdamper.nonlinear.indicators.conditioning import (
    ILL_CONDITIONED,
    SIGNIFICANT_DIGITS,
    backbone_conditions,
    equilibrated_condition,
    point_condition,
    reported,
)
from ringdamper.nonlinear.solvers.newton import Factorization
from ringdamper.nonlinear.stage import amplitude_grid, solve_backbone
from ringdamper.status import usable_status


def _system(n: int, condition: float, seed: int) -> tuple[np.ndarray, np.ndarray]:
    """``(J, scale)``: ``J = R A C⁻¹`` with ``A`` of singular values log-spaced from 1 to 1/condition and
    the row and column scalings ``R``, ``C`` over 10 decades (the residual's and the unknowns' units,
    what the equilibration removes), ``scale = diag(C)``: κ₁(D_r J D_c) is that of ``A`` equilibrated."""
    rng = np.random.default_rng(seed)
    U, _ = np.linalg.qr(rng.standard_normal((n, n)))
    V, _ = np.linalg.qr(rng.standard_normal((n, n)))
    A = (U * np.geomspace(1.0, 1.0 / condition, n)) @ V.T
    units = rng.permutation(np.geomspace(1e5, 1e-5, n))
    return np.geomspace(1e-5, 1e5, n)[:, None] * A / units, units


def _exact(J, scale):
    """Exact κ₁ of the equilibrated matrix D_r J D_c (numpy, through the inverse)."""
    A = J * scale
    A = A / np.max(np.abs(A), axis=1)[:, None]
    return np.linalg.cond(A, 1)


@pytest.mark.parametrize("condition", [1e2, 1e6, 1e10])
def test_estimate_is_within_a_factor_three_of_the_exact_condition_number(condition):
    """LAPACK's estimate (dgecon after the LU) of κ₁(D_r J D_c) lies within [1/3, 1] of numpy's exact
    value (Higham's estimator gives a lower bound, in practice within a factor of a few), and that within
    a factor n of the 2-norm condition number built in."""
    for seed in range(3):
        J, scale = _system(80, condition, seed)
        exact = _exact(J, scale)
        est = equilibrated_condition(J.copy(), None, scale)
        assert exact / 3 <= est <= exact * (1 + 1e-8), (seed, est, exact)
        assert condition / 80 <= est <= condition * 80, (seed, est)


def test_equilibration_removes_row_scaling_and_the_unknowns_scale():
    """κ of D_r J D_c does not depend on a row scaling of J (the residual's units), nor on the units of
    the unknowns when ``scale`` follows them (J D_u⁻¹ with scale D_u s)."""
    J, scale = _system(60, 1e7, 4)
    rows, units = np.geomspace(1e-8, 1e8, 60), np.geomspace(1e6, 1e-6, 60)
    ref = equilibrated_condition(J.copy(), None, scale)
    assert equilibrated_condition(rows[:, None] * J, None, scale) == pytest.approx(ref, rel=1e-6)
    assert equilibrated_condition(J / units, None, scale * units) == pytest.approx(ref, rel=1e-6)


def test_trivial_unknowns_are_eliminated_and_a_singular_jacobian_is_infinite():
    """With trivial unknowns T (unit columns in the core rows, coupled to the others through their own
    rows and the extra rows) κ is that of the Schur complement J_NN − J_NT J_TN, the system the Newton
    solves; a zero row gives inf."""
    rng = np.random.default_rng(5)
    n, n_core = 40, 38
    J, _ = _system(n, 1e5, 6)
    trivial = np.zeros(n_core, bool)
    trivial[[3, 10, 17]] = True
    T = np.flatnonzero(trivial)
    J[:n_core, T] = 0.0
    J[T, T] = 1.0
    J[n_core:, T] = rng.standard_normal((n - n_core, T.size))
    N = np.flatnonzero(~np.r_[trivial, False, False])
    schur = J[np.ix_(N, N)] - J[np.ix_(N, T)] @ J[np.ix_(T, N)]
    scale = np.ones(n)
    assert equilibrated_condition(J.copy(), trivial, scale) == pytest.approx(
        equilibrated_condition(schur, None, scale[N]), rel=1e-12)
    J[5] = 0.0
    with pytest.warns(LinAlgWarning, match="Singular matrix"):
        assert equilibrated_condition(J, trivial, scale) == np.inf


@pytest.fixture(scope="module")
def backbone(small_config, campaign_config):
    """The coarse default ring's backbone at the campaign's dNNM settings (H = 3, 30 amplitudes)."""
    from ringdamper.bench.dnnm import ring_inputs
    from ringdamper.studies.hub_calibration import crossing_speed

    cfg = {**small_config, "dnnm": campaign_config["dnnm"]}
    reduced, static = ring_inputs(cfg, (0.0, 0.0, 0.0))
    dnnm = cfg["dnnm"]
    bb, _, _, _ = solve_backbone(reduced, static, cfg, crossing_speed(cfg)[1], amplitude_grid(dnnm),
                                 dnnm["n_harmonics"], dnnm["n_time_samples"])
    return bb


def test_stuck_points_share_the_first_points_condition_number(backbone):
    """The stuck shortcut's points (iterations 0, zero ξ) get the κ of the first point, which equals
    their own computed from their Jacobians (the scaling argument of the module docstring), as reported;
    the slipping points get their own; the backbone's model is left as it was (every attribute the same
    object: the model is fixed, the gauge state lives in each solve)."""
    bb = backbone
    state = dict(vars(bb.model))
    kappa = backbone_conditions(bb)
    assert all(vars(bb.model)[k] is v for k, v in state.items())
    ok = usable_status(bb.status)
    assert np.all(np.isfinite(kappa[ok])) and np.all(np.isnan(kappa[~ok]))
    stuck = np.flatnonzero(bb.iterations == 0)
    assert stuck.size >= 5 and np.all(kappa[stuck] == kappa[0])
    direct = np.array([point_condition(bb, i) for i in stuck])
    np.testing.assert_allclose(direct, kappa[0], rtol=10.0 ** (1 - SIGNIFICANT_DIGITS))
    assert np.all(reported(direct) == kappa[0])
    slipping = np.flatnonzero(ok & (bb.iterations > 0))
    assert slipping.size >= 5 and len(set(kappa[slipping])) == slipping.size
    # the coarse ring is far from the flag: κ ≈ 1e5 (module docstring: the threshold 2.25e9)
    assert np.all(kappa[ok] < ILL_CONDITIONED)


def test_equilibrated_factorization_solves_the_system():
    """The LU of D_r A D_c (``Factorization(..., scale=...)``) solves J x = b, trivial unknowns included,
    within κ ε of the exact x in the scaled unknowns x/scale (here κ ≈ 1e4 while J itself, rows and
    unknowns over 10 decades, has κ ≈ 1e14); its condition estimate is that of
    :func:`equilibrated_condition`; without ``scale`` there is none."""
    rng = np.random.default_rng(7)
    n, n_core = 50, 48
    J, scale = _system(n, 1e4, 8)
    trivial = np.zeros(n_core, bool)
    trivial[[2, 9]] = True
    T = np.flatnonzero(trivial)
    J[:n_core, T] = 0.0
    J[T, T] = 1.0
    J[n_core:, T] = rng.standard_normal((n - n_core, T.size))
    exact = scale * rng.standard_normal(n)
    equilibrated = Factorization(J.copy(), trivial, n_core, scale=scale)
    kappa = equilibrated.condition()
    assert kappa == pytest.approx(equilibrated_condition(J.copy(), trivial, scale), rel=1e-12)
    error = np.max(np.abs(equilibrated.solve(J @ exact) - exact) / scale)
    assert error <= 10 * kappa * np.finfo(float).eps * np.max(np.abs(exact / scale))
    with pytest.raises(ValueError, match="scale"):
        Factorization(J.copy(), trivial, n_core).condition()


def test_continuation_estimates_are_the_points_own(backbone):
    """The continuation keeps the κ of the LU it formed at each grid value it solved (the slipping
    points): the same as the point's κ computed afresh from its Jacobian, to the reported digits."""
    bb = backbone
    mine = np.flatnonzero(np.isfinite(bb.condition))
    assert mine.size >= 5 and np.all(bb.iterations[mine] > 0)
    direct = np.array([point_condition(bb, i) for i in mine])
    np.testing.assert_allclose(bb.condition[mine], direct, rtol=10.0 ** (1 - SIGNIFICANT_DIGITS))
    np.testing.assert_array_equal(backbone_conditions(bb)[mine], reported(bb.condition[mine]))
