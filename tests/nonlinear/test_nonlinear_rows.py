"""The Newton system on the nonlinear contact rows only
(:mod:`ringdamper.nonlinear.harmonic_balance.nonlinear_rows`) against the full system's LU: the same
solution, to 1e-10 of its largest scaled entry, on states of the default ring where pairs stick, slip
and lift off, at H = 3 and H = 7, with the EPMC's bordering (ω and ξ columns, two rows) and with the
rigid-body gauge; and its order, the nonlinear rows plus the resonant stuck modes and the borders."""
import numpy as np
import pytest

from ringdamper.nonlinear.harmonic_balance.condensed import CondensedHBM, pole_modes
from ringdamper.nonlinear.harmonic_balance.nonlinear_rows import NonlinearRowsSolver, StuckBasis
from ringdamper.nonlinear.solvers.jacobian import bordered, dense
from ringdamper.nonlinear.solvers.newton import Factorization

from .systems import cyclic_structure, free_body, multi_dof

#: agreement of the two solves, relative to the largest entry of the solution (unknowns scaled)
TOL = 1e-10

#: per-pair amplitude of the contact motion, relative to the slip (tangential) and lift-off (normal)
#: displacements of its preload: (tangential, normal)
REGIMES = {"stick": (0.02, 0.02), "slip": (4.0, 0.3), "lift": (30.0, 4.0)}


def _full_solve(J, trivial, n_core, b):
    """The full system's LU solve, refined once on its residual (the reference)."""
    A = dense(J).copy(order="F")
    fac = Factorization(A.copy(order="F"), trivial, n_core)
    x = fac.solve(b)
    return x + fac.solve(b - A @ x)


def _check(model, y, omega, xi, rng, border=True, omega0=None):
    """Both solves of ``J x = b`` (b random) at ``(y, ω, ξ)``, the stuck receptances summed directly or
    (``omega0``) by their series about ``ω₀``; returns the solver and the evaluation."""
    basis = StuckBasis(model, model.contacts.stuck_stiffness(), omega0)
    ev = model.evaluate(y, omega, xi, model.initial_gauge())
    J = ev.J
    if border:
        J = bordered(J, np.column_stack([ev.dr_domega, ev.dr_dxi]), rng.standard_normal((2, model.n_core + 2)))
    b = rng.standard_normal(J.shape[0])
    solver = NonlinearRowsSolver(basis, J).factorize()
    x = solver.solve(b)
    reference = _full_solve(J, ev.trivial, model.n_core, b)
    scale = np.r_[model.core_scale(y), np.ones(J.shape[0] - model.n_core)]
    error = np.max(np.abs(x - reference) / scale) / np.max(np.abs(reference) / scale)
    assert error <= TOL, error
    return solver, ev


def _random_state(model, regimes, rng):
    """Unknowns whose contact slots move pair ``q`` in regime ``regimes[q]`` (:data:`REGIMES`)."""
    c = model.contacts
    N0 = np.maximum(c.N0, 1e-3 * np.max(c.N0))
    slip, lift = c.mu * N0 / c.kt, N0 / c.kn
    amp = np.array([[REGIMES[r][1] * lift[q], REGIMES[r][0] * slip[q], REGIMES[r][0] * slip[q]]
                    for q, r in enumerate(regimes)])                     # (npairs, 3)
    y = np.zeros(model.n_core)
    d = rng.standard_normal((model.C, model.npairs, 3)) * amp / np.sqrt(model.C)
    y[:model.n_d] = d.ravel()
    y[model.n_d:] = 1e-3 * np.max(np.abs(d)) * rng.standard_normal(model.n_core - model.n_d)
    return y


@pytest.mark.parametrize("amp", [1e-7, 2e-5, 3e-4])
def test_small_chain_with_pole_modes_and_an_intermittent_pair(amp):
    rng = np.random.default_rng(1)
    st, c = multi_dof(H=3)
    w0 = np.sqrt(st.modal(1).w2)
    model = CondensedHBM(st, c, 3, 32, explicit=pole_modes(st, 3, 0.9 * w0[1], 1.1 * w0[1]))
    y = np.r_[amp * rng.standard_normal(model.n_core)]
    for border in (False, True):
        _check(model, y, 1.05 * w0[1], 3.0, rng, border)


@pytest.mark.parametrize("amp", [1e-6, 1e-4, 3e-3])
def test_free_ring_held_by_friction_only_gauge(amp):
    """The cyclic toy with its ring free but for friction: stuck (held), partly slipping and all slipping
    (both rigid-body directions gauged, each one more reduced unknown)."""
    rng = np.random.default_rng(2)
    st, c, _ = cyclic_structure(H=3, ring_support=0.0)
    model = CondensedHBM(st, c, 3, 36)
    solver, ev = _check(model, amp * rng.standard_normal(model.n_core), 90.0, 1.0, rng)
    assert solver.ng == ev.gauge.shape[1]
    assert (amp > 1e-5) == (solver.ng > 0)


def test_free_body_gauge_in_slip():
    rng = np.random.default_rng(3)
    st, c = free_body(H=2)
    model = CondensedHBM(st, c, 2, 32)
    d = np.zeros((model.C, model.p))
    d[:, 1] = 5e-3 * rng.standard_normal(model.C)
    y = np.r_[d.ravel(), 5e-3 * rng.standard_normal(model.n_core - model.n_d)]
    solver, _ = _check(model, y, 150.0, 2.0, rng)
    assert solver.ng == 1


@pytest.fixture(scope="module")
def ring(small_config, campaign_config):
    """The coarse default ring's structure (harmonics up to 7), contacts and stuck frequency."""
    from ringdamper.bench.dnnm import ring_inputs
    from ringdamper.nonlinear.stage import contacts_from_static, structure_from_reduced, target_stuck_frequency
    from ringdamper.studies.hub_calibration import crossing_speed

    cfg = {**small_config, "dnnm": campaign_config["dnnm"],
           "reduction": {**small_config["reduction"], "n_harmonics": 7}}
    reduced, static = ring_inputs(cfg, (0.0, 0.0, 0.0))
    structure = structure_from_reduced(reduced, 7)
    contacts = contacts_from_static(static, cfg["contact"])
    return structure, contacts, target_stuck_frequency(structure, contacts, crossing_speed(cfg)[1])


@pytest.mark.parametrize("H", [3, 7])
@pytest.mark.parametrize("mix", ["stick", "mixed", "lift"])
def test_default_ring_states(ring, H, mix):
    """Random states of the coarse default ring: every pair stuck; a third each stuck, slipping and
    lifting off; every pair lifting (the ring's rigid-body directions gauged); the stuck receptances by
    their series about the stuck frequency. The order is that of the
    nonlinear rows plus the resonant stuck modes, the gauge and the two borders."""
    structure, contacts, omega0 = ring
    rng = np.random.default_rng(H * 10 + len(mix))
    model = CondensedHBM(structure, contacts, H, 16 * (H + 1),
                         explicit=pole_modes(structure, H, 0.9 * omega0, 1.1 * omega0))
    regimes = {"stick": ["stick"] * model.npairs, "lift": ["lift"] * model.npairs,
               "mixed": [list(REGIMES)[q % 3] for q in range(model.npairs)]}[mix]
    solver, ev = _check(model, _random_state(model, regimes, rng), 1.02 * omega0, 5.0, rng, omega0=omega0)
    nR, ne, ng, k = solver.sizes
    assert solver.order == nR + ne + ng + k and k == 2
    if mix == "stick":
        assert nR == 0 and ng == 0 and solver.order < model.n_core / 10
    else:
        assert solver.pairs.size == sum(r != "stick" for r in regimes)
        assert 0 < nR <= model.n_d and (mix == "lift" or nR < model.n_d)
    if mix == "lift":
        assert ng == ev.gauge.shape[1] > 0
