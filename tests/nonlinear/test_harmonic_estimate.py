"""The harmonic-truncation error estimate (ringdamper.nonlinear.indicators.harmonic_estimate) against solved
truncations: a one-DoF Jenkins oscillator, the separating-contact study's gap family, bad input."""
import numpy as np
import pytest

from ringdamper.nonlinear.harmonic_balance.epmc import epmc
from ringdamper.nonlinear.indicators.harmonic_estimate import (
    ESTIMATED,
    ZETA_FLOOR,
    estimate_raise,
    point_outputs,
    relative_changes,
)
from ringdamper.studies.method_limits.harmonics import FAMILIES, ZETA_S, separating_oscillator

from .systems import one_dof

GAP_ALPHA = np.geomspace(2e-3, 0.3, 40)            # the study's grid
FOUR = ESTIMATED[:4]                               # ω, ζ, γ, |q_res,z|


def _calibration(structure, contacts, alpha, H, H_to, samples, method="block"):
    """Per point of the backbone at ``H``: the actual relative changes (the backbone solved at ``H_to``)
    and the estimated ones, ``(actual, estimated)`` arrays (points, :data:`ESTIMATED`), and ζ at ``H``."""
    low = epmc(structure, contacts, alpha, H=H, nt=samples * H, tol=1e-12)
    high = epmc(structure, contacts, alpha, H=H_to, nt=samples * H_to, tol=1e-12)
    assert np.all(low.status == 0) and np.all(high.status == 0)
    out_low, out_high = point_outputs(low, ZETA_S), point_outputs(high, ZETA_S)
    actual, estimated, models = [], [], {}
    for i in range(alpha.size):
        before = {k: v[i] for k, v in out_low.items()}
        actual.append(list(relative_changes({k: v[i] for k, v in out_high.items()}, before).values()))
        e = estimate_raise(low, i, H_to, samples * H_to, ZETA_S, method, models, current=before)
        estimated.append([e.change[k] for k in ESTIMATED])
    return np.array(actual), np.array(estimated), out_low["zeta"]


@pytest.fixture(scope="module")
def gap():
    """The gap family (contact closing over part of the period) from H = 3 to H = 5, 32 samples a
    harmonic: the block step and the full Newton step."""
    p = FAMILIES["gap"]
    st, contacts = separating_oscillator(p["N0"], p["gap"], 5)
    actual, block, zeta = _calibration(st, contacts, GAP_ALPHA, 3, 5, 32)
    _, newton, _ = _calibration(st, contacts, GAP_ALPHA, 3, 5, 32, method="newton")
    return [_study_measure(c, zeta) for c in (actual, block, newton)]


def _study_measure(change, zeta):
    """The study's measure of the changes (docs/method_limits.md §2): ζ's relative to the family's
    largest ζ (where the pair only just closes ζ is ~1e-11, and its relative change says nothing)."""
    out = change.copy()
    out[:, 1] *= np.maximum(np.abs(zeta), ZETA_FLOOR) / np.max(zeta)
    return out


@pytest.mark.parametrize("H, H_to", [(1, 3), (3, 5)])
def test_one_dof_jenkins_estimate_is_the_raised_solution(H, H_to):
    """One DoF with a Jenkins element (stuck below μN/kt, then slipping over 30× that amplitude): the
    change of ω, ζ, γ and |q_res,z| from raising H (up to 1.4 % from H = 1 to 3, 0.1 % from 3 to 5) is
    estimated to 2 % of itself at nine in ten of the points and outputs where it exceeds 0.1 % (to 40 %
    at the others), and below 0.2 % where it does not (a few of those, of 1e-5 to 1e-3, the one step
    misses in sign); at the stuck points both vanish (ζ's over
    ``ZETA_FLOOR``: 1e-6)."""
    st, contacts = one_dof(H=5)
    a_slip = 0.3 * 10.0 / 50.0                              # μN/kt, displacement; modal = √m × that
    alpha = np.sqrt(2.0) * a_slip * np.geomspace(0.5, 30, 12)
    actual, estimated, _ = _calibration(st, contacts, alpha, H, H_to, 32)
    four = slice(0, 4)
    stuck = alpha < np.sqrt(2.0) * a_slip
    assert stuck.sum() == 2 and np.max(np.abs(actual[~stuck, four])) > (1e-2 if H == 1 else 1e-3)
    assert np.max(np.abs(estimated[stuck, four])) < 1e-6 and np.max(np.abs(actual[stuck, four])) < 1e-6
    big = np.abs(actual[:, four]) > 1e-3
    assert big.sum() >= (10 if H == 1 else 2)
    error = np.abs(estimated[:, four][big] / actual[:, four][big] - 1)
    assert np.max(error) < 0.4 and np.mean(error < 0.02) > 0.9, error
    assert np.max(np.abs(estimated[:, four][~big])) < 2e-3      # quiet where the change is
    # the amplitude equation holds in the step: the modal amplitude moves by the aliasing only
    assert np.max(np.abs(estimated[:, 4])) < 1e-6


def test_gap_family_estimate_flags_every_changing_point_and_passes_the_quiet_ones(gap):
    """Every point whose ω, ζ, γ or |q_res,z| moves by more than 1 % from H = 3 to 5 (the study's measure)
    has an estimate above the flag level (0.3 %), every point moving by less than 0.1 % one below it;
    both kinds occur."""
    actual, block, _ = gap
    act, est = np.max(np.abs(actual[:, :4]), axis=1), np.max(np.abs(block[:, :4]), axis=1)
    big, quiet = act > 0.01, act < 0.001
    assert big.sum() >= 5 and quiet.sum() >= 15
    assert np.all(est[big] > 0.003), (act[big], est[big])
    assert np.all(est[quiet] < 0.003), (act[quiet], est[quiet])


def test_gap_family_estimate_within_a_factor_of_the_actual_change(gap):
    """Where a point moves by more than 0.1 %, the largest estimated change of the four is within 2× of the
    actual one, and the estimated change of γ and |q_res,z| within 30 % of it wherever that exceeds 0.1 %
    (γ moves by up to 5 %, |q_res,z| by 0.6 %). The block step is the full Newton step to 10 % there."""
    actual, block, newton = gap
    act, est = np.max(np.abs(actual[:, :4]), axis=1), np.max(np.abs(block[:, :4]), axis=1)
    moved = act > 1e-3
    assert moved.sum() >= 15
    assert np.all((est[moved] / act[moved] > 0.5) & (est[moved] / act[moved] < 2)), est[moved] / act[moved]
    for k in (2, 3):
        big = np.abs(actual[:, k]) > 1e-3
        assert big.sum() >= 10
        np.testing.assert_allclose(block[big, k], actual[big, k], rtol=0.3)
        np.testing.assert_allclose(block[big, k], newton[big, k], rtol=0.1)


def test_bad_truncation_and_method_are_named():
    """A target truncation not above the backbone's, or above the structure's, and an unknown step rule
    raise, naming them, before any evaluation."""
    st, contacts = one_dof(H=5)
    bb = epmc(st, contacts, np.array([0.1, 0.2]), H=3, nt=96)
    with pytest.raises(ValueError, match="H_to = 3: must exceed"):
        estimate_raise(bb, 0, 3, 96, ZETA_S)
    with pytest.raises(ValueError, match="H_to = 7 exceeds the 5 harmonics"):
        estimate_raise(bb, 0, 7, 224, ZETA_S)
    with pytest.raises(ValueError, match="method: expected one of"):
        estimate_raise(bb, 0, 5, 160, ZETA_S, method="jacobi")


def test_estimate_gated_adaptive_pass_keeps_quiet_points_bitwise_and_raises_the_flagged_ones():
    """The preload family (a preloaded pair that lifts off at the top of the grid) adapted from H = 3 up to
    7 with the estimate gating the first raise of each watched point (``ESTIMATE_FLAG``, 0.3 %): the points
    it keeps at H = 3 carry the H = 3 continuation's outputs bitwise, some watched points are kept, the
    raised ones equal those of the pass without the estimate (to the Newton tolerance), and every point is
    within 1 % of H = 7 on ω, γ and |q_res,z| where fixed H = 3 is not."""
    from ringdamper.nonlinear.adaptive import ESTIMATE_FLAG, OUTPUTS, adapt_harmonics, backbone_outputs

    p = FAMILIES["preload"]
    st, contacts = separating_oscillator(p["N0"], p["gap"], 7)
    base = epmc(st, contacts, GAP_ALPHA, H=3, nt=96, tol=1e-10)
    plain = adapt_harmonics(base, contacts, 7, ZETA_S, tol=1e-10)
    gated = adapt_harmonics(base, contacts, 7, ZETA_S, tol=1e-10, estimate_flag=ESTIMATE_FLAG)
    at_base = backbone_outputs(base, contacts, ZETA_S)
    kept = gated.n_harmonics == 3
    assert gated.estimated >= 5 and gated.resolved < plain.resolved
    assert np.sum(kept & (plain.n_harmonics > 3)) >= 2                  # watched points the estimate passed
    for k in OUTPUTS:
        assert np.array_equal(gated.values[k][kept], at_base[k][kept], equal_nan=True), k
    raised = ~kept
    assert raised.sum() >= 4 and np.all(plain.n_harmonics[raised] > 3)
    for k in FOUR:
        np.testing.assert_allclose(gated.values[k][raised], plain.values[k][raised], rtol=1e-6)
    ref = backbone_outputs(epmc(st, contacts, GAP_ALPHA, H=7, nt=224, tol=1e-10), contacts, ZETA_S)
    error = np.max([np.abs(gated.values[k] / ref[k] - 1) for k in ("omega", "gamma", "q_res_peak")])
    fixed = np.max([np.abs(at_base[k] / ref[k] - 1) for k in ("omega", "gamma", "q_res_peak")])
    assert error < 0.01 < fixed, (error, fixed)
