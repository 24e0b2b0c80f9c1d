"""dNNM stage on the real chain (coarse mesh): linear limit, energy balance, E-EBM, failure file."""
import dataclasses

import numpy as np
import pytest

from ringdamper.fem.model import build_model
from ringdamper.geometry.sector import build_sector
from ringdamper.io import check_contract, read_netcdf
from ringdamper.nonlinear.fourier import default_nt
from ringdamper.nonlinear.harmonic_balance.epmc import _higher_model, epmc, linear_limit, resolve_point, stick_limit
from ringdamper.nonlinear.solvers import krylov
from ringdamper.nonlinear.stage import (
    contacts_from_static,
    failed_dnnm,
    first_unsolved_reason,
    run_dnnm,
    structure_from_reduced,
    target_stuck_frequency,
)
from ringdamper.reduction import modal_basis, reduce_sector, reduced_dataset
from ringdamper.static.stage import solve_static, static_dataset


@pytest.fixture(scope="module")
def chain(small_config):
    cfg = {**small_config, "mesh": {**small_config["mesh"], "element_order": 2}}
    model = build_model(build_sector(cfg, (0.0, 0.0, 0.0)), cfg)
    result, prob = solve_static(model, cfg)
    static = static_dataset(model, result, prob, (0.0, 0.0, 0.0), cfg["operation"]["speed_rpm"])
    rs = reduce_sector(model, cfg["operation"]["engine_order"], n_harmonics=3, n_fi=20, n_if=10)
    reduced = reduced_dataset(rs, (0.0, 0.0, 0.0), [modal_basis(rh, rs.response_index)
                                                    for rh in rs.harmonics])
    structure = structure_from_reduced(reduced, 1)
    contacts = contacts_from_static(static, cfg["contact"])
    omegas, _ = structure.stuck_modes(contacts.stuck_stiffness().ravel(), h=1)
    target_hz = omegas[1] / (2 * np.pi)  # the disk mode of the coarse model (1B is below it)
    return cfg, reduced, static, structure, contacts, target_hz


def test_linear_limit_and_energy_balance(chain):
    cfg, reduced, static, structure, contacts, target_hz = chain
    cfg = {**cfg, "dnnm": {**cfg["dnnm"], "structural_damping_ratio": 0.0}}
    w_stuck = target_stuck_frequency(structure, contacts, target_hz)
    ds = run_dnnm(reduced, static, cfg, target_hz, w_stuck)
    check_contract(ds)
    ok = np.isin(ds.status.values, (0, 3))
    assert np.all(ok), ds.status.values            # the whole amplitude grid is reached
    assert ds.attrs["unsolved_reason"] == ""
    # linear limit: stuck frequency, no damping, normalised frequency 2.195 exactly
    assert ds.frequency.values[0] * 2 * np.pi == pytest.approx(w_stuck, rel=1e-6)
    assert ds.omega0.values[0] == pytest.approx(2.195, rel=1e-6)
    assert abs(ds.zeta.values[0]) < 1e-8
    # EPMC energy identity on the real chain (zeta_s = 0): the artificial damping's energy per
    # cycle, pi omega sum h^2 xi |eta|^2, equals the energy the contact pairs dissipate (AFT)
    e_d = ds.energy_dissipated.values.sum(axis=1)
    slipping = ok & (ds.zeta.values > 1e-6)
    assert slipping.sum() >= 2
    assert np.allclose(ds.energy_damping.values[slipping], e_d[slipping], rtol=1e-6)
    assert np.all(ds.gamma.values[slipping] > 0)
    # softening: the frequency never rises above the stuck one along the backbone
    assert np.all(ds.frequency.values[ok] <= ds.frequency.values[0] * (1 + 1e-9))


def test_structure_is_the_same_arithmetic_from_the_reduction_and_from_its_file(chain, tmp_path):
    """The reduction's dataset holds strided views, reduced.nc read back contiguous arrays; BLAS
    rounds by the operands' layout, so the stage takes both to the same arrays, value and layout
    (the bench runs on the first, the campaign on the second)."""
    reduced = chain[1]
    reduced.to_netcdf(tmp_path / "reduced.nc")
    from_file = read_netcdf(tmp_path / "reduced.nc", "reduced")
    assert not reduced.contact_shape_real.isel(harmonic=1).values.flags.c_contiguous   # what is tested
    ours, theirs = structure_from_reduced(reduced, 3), structure_from_reduced(from_file, 3)
    for a, b in zip(ours.harmonics, theirs.harmonics):
        for name in ("B", "response", "force", "K"):
            x, y = getattr(a, name), getattr(b, name)
            assert np.array_equal(x, y) and x.strides == y.strides, name


def test_failed_geometry_has_the_variables_of_a_solved_one_all_nan(chain):
    """One declaration: a failure file has the same variables, dims, units and long_names as a
    success, its values all NaN, status 99 and the reason."""
    cfg, reduced, static, structure, contacts, target_hz = chain
    cfg = {**cfg, "dnnm": {**cfg["dnnm"], "n_amplitudes": 2}}
    ok = run_dnnm(reduced, static, cfg, target_hz, target_stuck_frequency(structure, contacts, target_hz))
    ds = failed_dnnm(cfg, (0.1, 0.2, 0.3), "RuntimeError: static solve failed", reduced.sizes["pair"])
    check_contract(ds)

    def declaration(d):
        return {k: (d[k].dims, d[k].attrs["units"], d[k].attrs["long_name"]) for k in d.variables}
    assert declaration(ds) == declaration(ok)
    assert dict(ds.sizes) == dict(ok.sizes)
    assert all(np.all(np.isnan(ds[k].values)) for k in ds.data_vars if k != "status")
    assert np.all(ds.status.values == 99) and "static solve failed" in ds.attrs["reason"]


def test_adaptive_harmonics_are_recorded_and_leave_quiet_points_bitwise(chain, monkeypatch):
    """dnnm.nc records the H of every point (``n_harmonics``). With ``dnnm.max_harmonics`` = 3 and a
    rule that raises every slipping point once (the coarse ring's grid has no lift-off, and ε_H is
    undefined at H = 1), the other points are bitwise those of the fixed-H run and the raised ones
    carry their H = 3 outputs: the EPMC energy identity (ζ_s = 0) holds at H = 3 and they differ
    from H = 1."""
    from ringdamper.nonlinear import adaptive

    cfg, reduced, static, structure, contacts, target_hz = chain
    cfg = {**cfg, "dnnm": {**cfg["dnnm"], "structural_damping_ratio": 0.0}}
    w_stuck = target_stuck_frequency(structure, contacts, target_hz)
    fixed = run_dnnm(reduced, static, cfg, target_hz, w_stuck)
    monkeypatch.setattr(adaptive, "needs_more_harmonics",
                        lambda point, previous, tol, onset: previous is None and point["zeta"] > 1e-6)
    adaptive_ds = run_dnnm(reduced, static, {**cfg, "dnnm": {**cfg["dnnm"], "max_harmonics": 3}},
                           target_hz, w_stuck)
    check_contract(adaptive_ds)
    H = adaptive_ds.n_harmonics.values
    assert adaptive_ds.n_harmonics.attrs["units"] == "1"
    assert np.all(fixed.n_harmonics.values == 1)
    assert adaptive_ds.attrs["max_harmonics"] == 3 and adaptive_ds.attrs["n_harmonics"] == 1
    raised = fixed.zeta.values > 1e-6
    assert raised.sum() >= 2 and adaptive_ds.attrs["harmonics_resolved"] == raised.sum()
    np.testing.assert_array_equal(H, np.where(raised, 3.0, 1.0))
    for k in ("zeta", "gamma", "q_res_z", "omega0", "energy_dissipated", "lifting_pairs", "status"):
        np.testing.assert_array_equal(adaptive_ds[k].values[~raised], fixed[k].values[~raised], err_msg=k)
    e_d = adaptive_ds.energy_dissipated.values[raised].sum(axis=1)
    np.testing.assert_allclose(adaptive_ds.energy_damping.values[raised], e_d, rtol=1e-6)
    assert np.all(adaptive_ds.highest_harmonic_energy.values[raised] > 0)      # defined at H = 3
    assert not np.allclose(adaptive_ds.gamma.values[raised], fixed.gamma.values[raised], rtol=1e-6)


def test_slip_onset_is_raised_until_it_stops_moving(chain):
    """The slip onset rule on the real chain (coarse ring, 12 amplitudes, H₀ = 1 up to 3, the AFT samples
    per harmonic kept): ε_H is undefined at H = 1 and no pair lifts off, so every raise is the onset's.
    The raised points are the first slipping point above the stuck ones and the next ones up to the first
    that moved by at most :data:`CHANGE_TOLERANCE` from H = 1 to 3; they carry the fixed H = 3 run's
    outputs, and every slipping point is then within the tolerance of it, where fixed H = 1 is not."""
    from ringdamper.nonlinear.adaptive import CHANGE_TOLERANCE, SLIP_ZETA

    cfg, reduced, static, structure, contacts, target_hz = chain
    w_stuck = target_stuck_frequency(structure, contacts, target_hz)

    def run(H, H_max):
        dnnm = {**cfg["dnnm"], "n_harmonics": H, "max_harmonics": H_max, "n_time_samples": 32 * H,
                "n_amplitudes": 12}
        return run_dnnm(reduced, static, {**cfg, "dnnm": dnnm}, target_hz, w_stuck)

    fixed1, fixed3, adaptive_ds = run(1, 1), run(3, 3), run(1, 3)
    assert np.all(np.isnan(fixed1.highest_harmonic_energy.values)) and np.all(fixed1.lifting_pairs.values == 0)
    names = ("omega0", "zeta", "gamma", "q_res_z")

    def change(a, b):                  # largest relative difference of the four outputs, per point
        return np.max([np.abs(a[k].values / b[k].values - 1) for k in names], axis=0)

    slipping = fixed1.zeta.values > SLIP_ZETA
    first = int(np.argmax(slipping))
    assert first > 0 and np.all(slipping[first:]) and not np.any(slipping[:first])
    moved = change(fixed1, fixed3) > CHANGE_TOLERANCE
    assert moved[first] and not moved[first:].all()           # what the rule must fix, and where it ends
    raised = adaptive_ds.n_harmonics.values == 3
    end = first + int(np.argmin(moved[first:]))               # the first slipping point that did not move
    np.testing.assert_array_equal(np.flatnonzero(raised), np.arange(first, end + 1))
    assert adaptive_ds.attrs["harmonics_resolved"] == raised.sum()
    assert np.all(change(adaptive_ds, fixed3)[raised] < 1e-5)     # the H = 3 solutions (ζ to ~1e-6)
    assert np.all(change(adaptive_ds, fixed3)[slipping] <= CHANGE_TOLERANCE)
    for k in names + ("status",):                              # the others untouched
        np.testing.assert_array_equal(adaptive_ds[k].values[~raised], fixed1[k].values[~raised], err_msg=k)


def _stuck_mode_of(chain):
    cfg, reduced, static, structure, contacts, target_hz = chain
    omega = target_stuck_frequency(structure, contacts, target_hz)
    omegas, phi = structure.stuck_modes(contacts.stuck_stiffness().ravel(), h=1)
    return structure, contacts, omega, phi[:, int(np.argmin(np.abs(omegas - omega)))]


def test_stuck_shortcut_equals_newton_on_the_stuck_points(chain):
    """Below the stick limit the shortcut (polished stuck mode scaled by alpha, no continuation)
    gives the Newton solution of every grid point: omega, xi, the contact slots and the modal
    coordinates within 1e-10 relative (Newton run to 1e-13 without the shortcut; the continuation
    tolerance is 1e-8)."""
    structure, contacts, omega, phi = _stuck_mode_of(chain)
    onset = stick_limit(structure, contacts, phi)
    alpha = onset * np.geomspace(0.01, 0.9, 6)
    fast = epmc(structure, contacts, alpha, H=1, omega_target=omega)
    newton = epmc(structure, contacts, alpha, H=1, omega_target=omega, tol=1e-13, stuck_shortcut=False)
    assert np.all(fast.status == 0) and np.all(newton.status == 0)
    assert np.all(fast.iterations == 0) and np.all(newton.iterations[1:] > 0)   # the shortcut was taken
    assert np.max(np.abs(fast.omega / newton.omega - 1)) <= 1e-10
    assert np.max(np.abs(fast.xi - newton.xi) / newton.omega) <= 1e-10
    # contact slots relative to their largest, modal coordinates of every harmonic relative to the
    # amplitude (sum_r |eta_1,r|^2 = alpha^2)
    scale_d = np.abs(newton.d).reshape(alpha.size, -1).max(axis=1)
    assert np.max(np.abs(fast.d - newton.d).reshape(alpha.size, -1).max(axis=1) / scale_d) <= 1e-10
    for a, b in zip(fast.eta, newton.eta):
        assert np.max(np.abs(a - b).max(axis=1) / alpha) <= 1e-10


def test_stick_limit_is_the_slip_onset(chain):
    """The stick limit includes the normal-force variation: just below it (0.999) the AFT solution
    is the linear stuck mode (zeta = 0, omega stuck), just above it (1.001) a pair slips
    (zeta > 0). Nt = 512 samples resolve the onset to (1/cos(pi/512) - 1) = 2e-5."""
    structure, contacts, omega, phi = _stuck_mode_of(chain)
    onset = stick_limit(structure, contacts, phi)
    assert onset < linear_limit(structure, contacts, phi)      # the preload falls during the period
    bb = epmc(structure, contacts, onset * np.array([0.999, 1.001]), H=1, nt=512, omega_target=omega,
              tol=1e-12, stuck_shortcut=False)
    assert np.all(bb.status == 0)
    assert abs(bb.zeta[0]) <= 1e-12 and bb.omega[0] == pytest.approx(omega, rel=1e-10)
    assert bb.zeta[1] > 1e-9


def test_lagged_tangents_trace_the_backbone_of_exact_ones(chain, monkeypatch):
    """Tangents by GMRES on a lagged factorisation (``krylov.MIN_SIZE`` = 0) against tangents from a
    fresh LU at every point (``MIN_SIZE`` above the system size): the same statuses and, at every
    converged point, the same ω (2e-8 relative), ζ (2e-8 absolute) and γ (2e-8/ζ relative): each run
    lies within Newton's tolerance of one root, 1e-8 in the unknowns with ξ scaled by ω, i.e. 1e-8
    in ω and ζ and, γ being proportional to the damping, ~1e-8/ζ relative in γ (measured: ω 3.8e-9,
    γ 9e-8); a switch to another branch moves them by 1e-2 or more."""
    cfg, reduced, static, structure, contacts, target_hz = chain
    w_stuck = target_stuck_frequency(structure, contacts, target_hz)
    runs = []
    for size in (0, 10**9):
        monkeypatch.setattr(krylov, "MIN_SIZE", size)
        runs.append(run_dnnm(reduced, static, cfg, target_hz, w_stuck))
    _same_backbone(*runs)


def test_quasi_newton_correctors_trace_the_backbone_of_chord_ones(chain, monkeypatch):
    """The EPMC's correctors with quasi-Newton steps on their factorisation (the default) against
    chord steps: the same statuses and points within Newton's tolerance of one root, as for the
    lagged tangents above."""
    from ringdamper.nonlinear.harmonic_balance import epmc as epmc_module

    cfg, reduced, static, structure, contacts, target_hz = chain
    w_stuck = target_stuck_frequency(structure, contacts, target_hz)
    quasi = run_dnnm(reduced, static, cfg, target_hz, w_stuck)
    chord_steps = dataclasses.replace(epmc_module.default_steps(), quasi_newton=False)
    monkeypatch.setattr(epmc_module, "default_steps", lambda: chord_steps)
    _same_backbone(quasi, run_dnnm(reduced, static, cfg, target_hz, w_stuck))


def _same_backbone(a, b):
    """Same statuses; at every converged or held point ω within 2e-8 relative, ζ within 2e-8 and γ
    within 2e-8/ζ relative (each run within Newton's tolerance of one root)."""
    assert np.array_equal(a.status.values, b.status.values)
    ok = np.isin(b.status.values, (0, 3))
    assert ok.all() and np.sum(b.zeta.values > 1e-6) >= 2
    assert np.allclose(a.frequency.values[ok], b.frequency.values[ok], rtol=2e-8, atol=0)
    assert np.max(np.abs(a.zeta.values - b.zeta.values)[ok]) <= 2e-8
    gamma, zeta = b.gamma.values[ok], np.abs(b.zeta.values[ok])
    assert np.all(np.abs(a.gamma.values[ok] - gamma) * zeta <= 2e-8 * gamma)


def test_where_the_continuation_stopped_is_recorded(chain, monkeypatch):
    """A continuation that cannot reach the top of the grid (one Newton iteration a corrector, steps of at
    least a third of log α's range, so every corrector fails) records its first unsolved amplitude and the
    driver's reason in ``unsolved_reason``."""
    from ringdamper.nonlinear.harmonic_balance import epmc as epmc_module

    cfg, reduced, static, structure, contacts, target_hz = chain
    w_stuck = target_stuck_frequency(structure, contacts, target_hz)
    steps = epmc_module.StepControl(initial=2.0, minimum=1.5, maximum=2.0, corrector=1)
    monkeypatch.setattr(epmc_module, "default_steps", lambda: steps)
    ds = run_dnnm(reduced, static, cfg, target_hz, w_stuck)
    status = ds.status.values
    first = int(np.flatnonzero(status == 1)[0])
    assert ds.attrs["unsolved_reason"].startswith(f"alpha = {ds.amplitude.values[first]:.4g}: ")
    assert "step below minimum" in ds.attrs["unsolved_reason"]
    assert first_unsolved_reason(np.array([1e-6, 1e-5]), [0, 3], ["", ""]) == ""


@pytest.fixture(scope="module")
def raised(chain):
    """The coarse ring's backbone at H = 1 on a structure with harmonics up to 3, a slipping point the
    contacts hold and a point whose rigid-body direction is pinned."""
    cfg, reduced, static, structure, contacts, target_hz = chain
    structure = structure_from_reduced(reduced, 3)
    dnnm = cfg["dnnm"]
    alpha = np.geomspace(dnnm["amplitude_min"], dnnm["amplitude_max"], dnnm["n_amplitudes"])
    backbone = epmc(structure, contacts, alpha, H=1,
                    omega_target=target_stuck_frequency(structure, contacts, target_hz))
    held = int(np.flatnonzero((backbone.status == 0) & (backbone.zeta > 1e-6))[0])
    pinned = next(i for i in range(alpha.size) if backbone.pinned[i].shape[1])
    assert not backbone.pinned[held].shape[1]
    return backbone, held, pinned


def test_raised_points_share_one_problem_with_their_own_gauge_state(raised):
    """The problem at the higher H is built once for the points of a backbone (``resolve_point(...,
    models=...)``, as the adaptive pass raises them) and each point's solve has its own gauge state: a
    point that the contacts hold, solved on it after a point whose rigid-body direction is pinned, equals
    the point solved on a fresh problem to rounding (the fresh one's receptance series are expanded about
    its own start; coarse ring, H = 1 raised to 3)."""
    backbone, held, pinned = raised
    fresh, why = resolve_point(backbone, held, 3)
    assert fresh is not None, why
    models = {}
    other, why = resolve_point(backbone, pinned, 3, models=models)
    (model,) = models.values()
    assert other is not None and other.pinned[0].shape[1], why      # the other point's solve pins
    shared, why = resolve_point(backbone, held, 3, models=models)
    assert shared is not None, why
    assert shared.model is model and len(models) == 1
    np.testing.assert_allclose([shared.omega[0], shared.xi[0]], [fresh.omega[0], fresh.xi[0]], rtol=1e-12)
    np.testing.assert_allclose(shared.d[0], fresh.d[0], rtol=0, atol=1e-10 * np.max(np.abs(fresh.d[0])))


def _arrays(value, prefix="", seen=None) -> dict:
    """Every array reachable from ``value`` through lists, tuples, dicts and the attributes of the solver's
    own objects, as ``path -> (dtype, shape, bytes)`` (scalars by value)."""
    seen = set() if seen is None else seen
    if isinstance(value, np.ndarray):
        return {prefix: (value.dtype.str, value.shape, value.tobytes())}
    if isinstance(value, (list, tuple)):
        return {k: v for i, item in enumerate(value) for k, v in _arrays(item, f"{prefix}[{i}]", seen).items()}
    if isinstance(value, dict):
        return {k: v for key, item in value.items() for k, v in _arrays(item, f"{prefix}.{key}", seen).items()}
    if type(value).__module__.startswith("ringdamper.nonlinear") and id(value) not in seen:
        seen.add(id(value))
        return {k: v for key, item in vars(value).items() for k, v in _arrays(item, f"{prefix}.{key}", seen).items()}
    return {prefix: repr(value)}


def test_a_shared_problem_solves_its_points_alike_in_either_order_and_stays_as_built(raised):
    """The adaptive pass's sharing: a point the contacts hold and a point whose rigid-body direction is
    pinned, solved again at H = 3 one after the other on one problem (``resolve_point(..., models=...)``),
    give the same solutions to the bit in either order (each order on a problem built alike), and the solves
    leave the problem as it was built: every array of it, its modal data and receptance series, the same
    bytes (its structure and contacts, inputs, not compared), and setting an attribute raises."""
    backbone, held, pinned = raised
    nt = default_nt(3)
    solved = {}
    for order in ((held, pinned), (pinned, held)):
        model = _higher_model(backbone, 3, nt, (backbone.omega[held], backbone.xi[held]))
        built = _arrays({k: v for k, v in vars(model).items() if k not in ("structure", "contacts")})
        models = {(3, nt): model}
        solved[order] = {i: resolve_point(backbone, i, 3, models=models) for i in order}
        assert _arrays({k: v for k, v in vars(model).items() if k not in ("structure", "contacts")}) == built
        assert all(b.model is model for b, _ in solved[order].values())
    with pytest.raises(AttributeError, match="fixed once built"):
        model.H = 5
    first, second = solved.values()
    for i in (held, pinned):
        (a, why), (b, _) = first[i], second[i]
        assert a is not None, why
        for name in ("omega", "xi", "d", "lam", "drift", "iterations"):
            assert np.array_equal(getattr(a, name), getattr(b, name)), (i, name)
        assert all(np.array_equal(x, y) for x, y in zip(a.eta, b.eta)) and np.array_equal(a.pinned[0], b.pinned[0])
    assert first[pinned][0].pinned[0].shape[1] and not first[held][0].pinned[0].shape[1]
