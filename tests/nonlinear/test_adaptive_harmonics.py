"""Adaptive harmonic truncation along a backbone (ringdamper.nonlinear.adaptive): the separating-contact
study's gap family against H = 11, quiet points untouched, failed higher-H solves, the config rule."""
import numpy as np
import pytest

from ringdamper.campaign.forced_check import EEBMBackbone
from ringdamper.config import ConfigError, load_config, validate_config
from ringdamper.nonlinear.adaptive import OUTPUTS, adapt_harmonics, backbone_outputs
from ringdamper.nonlinear.harmonic_balance.epmc import epmc
from ringdamper.studies.method_limits.harmonics import FAMILIES, ZETA_S, backbone, separating_oscillator

ALPHA = np.geomspace(2e-3, 0.3, 40)          # the study's grid
TOL = 1e-10                                   # the study's Newton tolerance


@pytest.fixture(scope="module")
def gap():
    """The gap family: H = 11 reference, fixed H = 3 (the study's nt = 96) and the adaptive result
    from that H = 3 continuation up to H = 7."""
    p = FAMILIES["gap"]
    ref, _, _ = backbone(p["N0"], p["gap"], 11, ALPHA)
    st, contacts = separating_oscillator(p["N0"], p["gap"], 7)
    base = epmc(st, contacts, ALPHA, H=3, nt=96, tol=TOL)
    return ref, base, contacts, adapt_harmonics(base, contacts, 7, ZETA_S, tol=TOL)


def _errors(values: dict, ref) -> dict:
    """The study's errors against ``ref``: ω at equal α, ζ at equal α relative to the largest
    reference ζ, and the E-EBM amplitude at equal forcing (read as the campaign reads it)."""
    ok = ref.status == 0
    curve = EEBMBackbone.from_arrays(ALPHA, values["q_res_peak"], values["gamma"], values["omega"],
                                     values["status"])
    ref_curve = EEBMBackbone.from_arrays(ALPHA, ref.q_res_peak, ref.gamma, ref.omega, ref.status)
    amplitude = [curve.at_forcing(g)["q"] / ref_curve.at_forcing(g)["q"] - 1 for g in ref.gamma[ok]]
    return {"omega": np.nanmax(np.abs(values["omega"][ok] / ref.omega[ok] - 1)),
            "zeta": np.nanmax(np.abs(values["zeta"][ok] - ref.zeta[ok])) / np.nanmax(ref.zeta[ok]),
            "amplitude": np.nanmax(np.abs(amplitude))}


def test_gap_family_adaptive_is_within_one_percent_of_h11_where_h3_is_not(gap):
    """Where the pair closes over part of the period, fixed H = 3 is off by 26 % in ζ and 3 % in the
    amplitude at equal forcing; raising H where ε_H > THRESHOLD brings the amplitude and ω within
    1 % of H = 11 and ζ within 5 % (ζ of short closures converges slowest in H, docs/method_limits.md
    §2: 4.7 % at H = 5, 6 % at H = 7, 3 % at H = 9)."""
    ref, base, contacts, adaptive = gap
    fixed = _errors(backbone_outputs(base, contacts, ZETA_S), ref)
    assert fixed["zeta"] > 0.2 and fixed["amplitude"] > 0.02           # what the adaptation must fix
    err = _errors(adaptive.values, ref)
    assert err["amplitude"] < 0.01 and err["omega"] < 0.01, err
    assert err["zeta"] < 0.05, err
    assert np.all(adaptive.values["highest_harmonic_energy"] < 3e-4)    # every point below the threshold
    assert set(adaptive.n_harmonics) == {3, 5}                          # raised where needed, not everywhere
    assert adaptive.resolved == np.sum(adaptive.n_harmonics > 3)


def test_quiet_points_keep_the_base_truncation_bitwise(gap):
    """A point whose indicators stay below their thresholds keeps H₀ and exactly its continuation
    solution's outputs; a raised point's ε_H at H₀ was above the threshold."""
    ref, base, contacts, adaptive = gap
    at_base = backbone_outputs(base, contacts, ZETA_S)
    quiet = adaptive.n_harmonics == 3
    assert quiet.sum() >= 20
    for k in OUTPUTS:
        assert np.array_equal(adaptive.values[k][quiet], at_base[k][quiet], equal_nan=True), k
    assert np.all(at_base["highest_harmonic_energy"][~quiet] > 3e-4)
    assert not np.any(at_base["highest_harmonic_energy"][quiet] > 3e-4)


def test_failed_higher_newton_keeps_the_last_converged_truncation(gap):
    """A Newton tolerance no iterate meets: every raise fails, each point keeps H₀ and its outputs,
    and the points' reasons say which H failed."""
    ref, base, contacts, _ = gap
    adaptive = adapt_harmonics(base, contacts, 7, ZETA_S, tol=1e-300)
    raised = backbone_outputs(base, contacts, ZETA_S)["highest_harmonic_energy"] > 3e-4
    assert np.all(adaptive.n_harmonics == 3)
    assert len(adaptive.notes) == raised.sum() == adaptive.resolved
    assert all("Newton at H = 5" in adaptive.reason[i] and "kept H = 3" in adaptive.reason[i]
               for i in np.flatnonzero(raised))
    assert np.array_equal(adaptive.values["gamma"], backbone_outputs(base, contacts, ZETA_S)["gamma"],
                          equal_nan=True)


def test_max_harmonics_is_bounded_by_the_reduction_and_the_base():
    config = load_config()
    config["dnnm"]["max_harmonics"] = config["reduction"]["n_harmonics"] + 2
    with pytest.raises(ConfigError, match=r"dnnm.max_harmonics = \d+ must lie in \[dnnm.n_harmonics, "
                                          r"reduction.n_harmonics\]"):
        validate_config(config)
    config["dnnm"]["max_harmonics"] = config["dnnm"]["n_harmonics"] - 1
    with pytest.raises(ConfigError, match="dnnm.max_harmonics"):
        validate_config(config)


def test_higher_h_continuation_takes_the_arc_budget_given(gap, monkeypatch):
    """Where Newton at the higher H fails from both starts, the point is continued at that H from the
    point below; that continuation gets the arc-length budget passed in (the stage's ``ARC_POINTS``),
    not the driver's default, and solves the point."""
    import ringdamper.nonlinear.adaptive as adaptive_module
    import ringdamper.nonlinear.harmonic_balance.epmc as epmc_module

    ref, base, contacts, _ = gap
    resolve, arc = adaptive_module.resolve_point, epmc_module.natural_then_arclength
    calls, budgets = [0], []

    def first_only(*args, **kwargs):                   # Newton at H = 5 only for the first raised point
        calls[0] += 1
        return resolve(*args, **kwargs) if calls[0] == 1 else (None, "refused")

    def recorded(*args, **kwargs):
        budgets.append(args[3].max_points)                 # natural_then_arclength(problem, z0, grid, steps)
        return arc(*args, **kwargs)

    monkeypatch.setattr(adaptive_module, "resolve_point", first_only)
    monkeypatch.setattr(epmc_module, "natural_then_arclength", recorded)
    adaptive = adapt_harmonics(base, contacts, 5, ZETA_S, tol=TOL, max_arc_points=7)
    assert budgets and set(budgets) == {7}
    assert np.sum(adaptive.n_harmonics == 5) == len(budgets) + 1       # each of them solved at H = 5


def test_raise_over_its_lu_budget_keeps_the_lower_truncation_flagged_with_its_error(gap):
    """A budget of one LU per raise on raises that need more (every converging raise of the gap family
    takes one LU, so the Newton tolerance is one no iterate meets): every raise stops at its second LU,
    each point keeps H₀ and its outputs bitwise, and carries flag 1 and a finite estimated error, the
    estimate of raising it to H₀ + 2 at H₀, which exceeds the estimate's flag level (0.3 %) wherever
    the solved raise (default budget, tolerance 1e-10) moves ω, γ or |q_res,z| by more than 1 %; the
    other points have flag 0 and no error."""
    from ringdamper.nonlinear.adaptive import ESTIMATE_FLAG, time_samples
    from ringdamper.nonlinear.indicators.harmonic_estimate import estimate_raise

    ref, base, contacts, solved = gap
    at_base = backbone_outputs(base, contacts, ZETA_S)
    adaptive = adapt_harmonics(base, contacts, 7, ZETA_S, tol=1e-300, raise_budget_lus=1)
    flag, err = adaptive.values["truncation_flag"], adaptive.values["truncation_error"]
    flagged = np.flatnonzero(flag)
    assert np.all(adaptive.n_harmonics == 3) and len(flagged) == len(adaptive.notes) >= 5
    assert set(flag[flagged]) == {1} and np.array_equal(flagged, np.flatnonzero(solved.n_harmonics > 3))
    for k in OUTPUTS:
        assert np.array_equal(adaptive.values[k], at_base[k], equal_nan=True), k
    assert np.all(np.isfinite(err[flagged])) and np.all(np.isnan(np.delete(err, flagged)))
    assert all("LU budget of 1 factorisations exceeded" in adaptive.reason[i] for i in flagged)
    nt = time_samples(5, 3, 96)
    assert all(err[i] == estimate_raise(base, i, 5, nt, ZETA_S).largest for i in flagged)
    moved = [max(abs(solved.values[k][i] / at_base[k][i] - 1) for k in ("omega", "gamma", "q_res_peak"))
             for i in flagged]                          # what the solved raise changed (default budget)
    assert np.sum(np.array(moved) > 0.01) >= 3
    assert np.all(err[flagged][np.array(moved) > 0.01] > ESTIMATE_FLAG)


def test_default_raise_budget_leaves_the_adaptive_result_unchanged(gap):
    """The default budget (RAISE_BUDGET_LUS) stops no raise of the gap family: every output and
    truncation equals that of an unbounded pass bitwise, and no point is flagged."""
    ref, base, contacts, bounded = gap
    unbounded = adapt_harmonics(base, contacts, 7, ZETA_S, tol=TOL, raise_budget_lus=None)
    assert np.array_equal(bounded.n_harmonics, unbounded.n_harmonics)
    for k in OUTPUTS:
        assert np.array_equal(bounded.values[k], unbounded.values[k], equal_nan=True), k
    assert not np.any(bounded.values["truncation_flag"]) and np.all(np.isnan(bounded.values["truncation_error"]))


def test_failed_raise_is_flagged_with_its_error(gap):
    """Without a budget, a raise whose Newton cannot converge (tolerance 1e-300) runs through every start
    and is flagged 2, with a finite error."""
    ref, base, contacts, _ = gap
    adaptive = adapt_harmonics(base, contacts, 5, ZETA_S, tol=1e-300, raise_budget_lus=None)
    flagged = np.flatnonzero(adaptive.values["truncation_flag"])
    assert len(flagged) == len(adaptive.notes) > 0
    assert set(adaptive.values["truncation_flag"][flagged]) == {2}
    assert np.all(np.isfinite(adaptive.values["truncation_error"][flagged]))


def test_raise_budget_must_be_a_positive_integer():
    config = load_config()
    for bad in (0, 2.5):
        config["dnnm"]["raise_budget_lus"] = bad
        with pytest.raises(ConfigError, match="dnnm.raise_budget_lus"):
            validate_config(config)
