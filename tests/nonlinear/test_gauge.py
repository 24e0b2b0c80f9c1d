"""Gauge of zero-frequency modes: a free mass held only by friction on an oscillator.

While the contact sticks, the free body's mean position is determined (its equilibrium is a
regular equation); once the contact has lost its memory the position is undetermined, the
explicit gauge ``η_Z = η_ref`` replaces that equilibrium, the DC problem stays regular, and every
physical output is independent of the gauge value. An unbalanced case (normal load in phase with
the slip: mean friction force on the free body) is reported with status DRIFT, and so is a free
ring in the cyclic toy."""
from dataclasses import replace

import numpy as np
import pytest

from ringdamper.nonlinear.harmonic_balance.epmc import EPMCProblem, epmc
from ringdamper.nonlinear.solvers.newton import newton
from ringdamper.status import Status

from .systems import cyclic_structure, free_body


def _backbone(normal_coupling=0.0, H=3):
    st, c = free_body(H=H, normal_coupling=normal_coupling)
    a_slip = 1.0e-3
    return epmc(st, c, a_slip * np.logspace(-1.5, 0.25, 8), H=H, nt=64, tol=1e-12)


def _resolve(bb, i, eta_ref):
    model = bb.model
    gauge = replace(bb.problem(i).gauge, reference=np.atleast_1d(eta_ref).astype(float))
    problem = EPMCProblem(model, bb.phase_index, gauge=gauge)
    z0 = bb.unknowns(i)
    z0[model.eta_slices[0].start + model.zero_modes] = gauge.reference
    res = newton(lambda z, jac: problem.fun(z, np.log(bb.alpha[i]), jac), z0, problem.scale,
                 tol=1e-12, max_iter=30)
    assert res.converged
    return res


def test_free_body_backbone_is_regular():
    bb = _backbone()
    assert np.all(bb.status == Status.CONVERGED)
    ev_stick = bb.model.evaluate(bb.unknowns(0)[:-2], bb.omega[0], bb.xi[0], bb.problem(0).gauge)
    ev_slip = bb.model.evaluate(bb.unknowns(7)[:-2], bb.omega[7], bb.xi[7], bb.problem(7).gauge)
    assert ev_stick.drift.size == 0                   # held by the stuck contact: no gauge
    assert ev_slip.drift.size == 1                    # memory lost: gauge on the rigid mode
    assert bb.zeta[0] == pytest.approx(0.0, abs=1e-14) and bb.zeta[7] > 1e-3
    assert np.max(bb.drift) < 1e-10                   # symmetric orbit: no mean force


def test_outputs_do_not_depend_on_gauge_value():
    bb = _backbone()
    model = bb.model
    zpos = model.eta_slices[0].start + model.zero_modes
    i = 7                                             # slipping, memory lost
    a, b = _resolve(bb, i, 0.0), _resolve(bb, i, 0.37)
    scale = np.abs(a.z[:-2]).max()                     # Newton round-off relative to the state
    assert a.z[zpos] == pytest.approx(0.0, abs=1e-10 * scale) and b.z[zpos] == pytest.approx(0.37)
    for k in (-2, -1):                                # ω and ξ
        assert b.z[k] == pytest.approx(a.z[k], rel=1e-10)
    ea, eb = a.payload, b.payload
    assert np.allclose(ea.lam, eb.lam, rtol=0, atol=1e-9 * np.abs(ea.lam).max())
    assert np.allclose(ea.d[1:], eb.d[1:], rtol=0, atol=1e-9 * np.abs(ea.d).max())
    for h in range(1, model.H + 1):
        assert np.allclose(ea.eta[h], eb.eta[h], atol=1e-9 * np.abs(ea.eta[1]).max())
    # the free body moved rigidly by the gauge difference: relative DC shift = Ψ_Z Δη
    psi = model.modal[0].Psi[:, model.S[0][model.zero_modes]].ravel()
    assert np.allclose(eb.d[0] - ea.d[0], 0.37 * psi, atol=1e-9 * abs(0.37 * psi).max())
    # in stick the position is determined: the gauge value is not used
    s, t = _resolve(bb, 0, 0.0), _resolve(bb, 0, 0.37)
    assert s.z[zpos] == pytest.approx(t.z[zpos], abs=1e-10 * np.abs(s.z[:-2]).max())


def test_unbalanced_free_body_is_flagged():
    """Normal load in phase with the tangential motion: once the contact loses its memory the
    mean friction force on the free body is not zero; the point is converged but flagged."""
    bb = _backbone(normal_coupling=0.3)
    assert bb.status[0] == Status.CONVERGED
    assert np.any(bb.status == Status.DRIFT)
    drifting = bb.status == Status.DRIFT
    assert np.all(bb.drift[drifting] > 1e-6) and np.all(np.isfinite(bb.omega[drifting]))
    assert "ratchets" in bb.reason[int(np.argmax(drifting))]


def test_free_ring_in_cyclic_toy_is_flagged():
    st, c, _ = cyclic_structure(H=1, ring_support=0.0)
    bb = epmc(st, c, np.geomspace(1e-4, 3e-2, 8), H=1, nt=60, mode=0)
    assert bb.status[0] == Status.CONVERGED
    assert bb.status[-1] == Status.DRIFT


def _free_ring_model():
    from ringdamper.nonlinear.harmonic_balance.condensed import CondensedHBM

    st, c, _ = cyclic_structure(H=2, ring_support=0.0)
    return CondensedHBM(st, c, 2, 32)


def test_pinned_direction_stays_gauged_and_its_jacobian_is_exact():
    """A pinned rigid-body direction (one of the free ring's two) is gauged even while a stuck
    contact would hold it: its row is ``gᵀ(η_Z − η_ref)``, the dropped equilibrium is the drift,
    the other direction keeps its equilibrium, and the Jacobian matches central differences."""
    from .test_jacobians import _check_problem

    model = _free_ring_model()
    assert model.zero_modes.size == 2
    rng = np.random.default_rng(4)
    y = np.zeros(model.n_core)
    y[:model.n_d] = 1e-5 * rng.standard_normal(model.n_d)          # stuck: both directions held
    y[model.n_d:] = 1e-5 * rng.standard_normal(model.n_core - model.n_d)
    held = model.evaluate(y, 100.0, 1.0, model.initial_gauge())
    assert held.drift.size == 0
    g = np.array([[0.6], [0.8]])
    state = model.initial_gauge(np.array([0.1, -0.2]))
    state, added = state.pin(g)
    assert added and not state.pin(-2.0 * g)[1]                    # a direction is pinned once
    ev = model.evaluate(y, 100.0, 1.0, state)
    rows = model.eta_slices[0].start + model.zero_modes
    assert ev.drift.size == 1 and np.allclose(ev.gauge, g)
    h = np.array([[0.8], [-0.6]])                                  # the held complement
    assert ev.r[rows[1]] == pytest.approx((g.T @ (y[rows] - state.reference)).item(), rel=1e-12)
    assert abs(ev.r[rows[0]]) == pytest.approx(abs((h.T @ held.r[rows]).item()), rel=1e-9)
    assert ev.drift[0] == pytest.approx((g.T @ held.r[rows]).item(), rel=1e-9)
    prob = EPMCProblem(model, phase_index=model.slot_index(1, True, 1), gauge=state)
    z = np.r_[y, 100.0, 1.0]
    _check_problem(lambda x: prob.fun(x, np.log(1e-3)), z, prob.scale(z))


def test_lost_hold_is_pinned_after_a_failed_step():
    """Directions whose hold an evaluation found lost are pinned by ``pin_seen`` (called by the
    continuation after a failed corrector), and forgotten at the next accepted point otherwise."""
    model = _free_ring_model()
    rng = np.random.default_rng(8)
    y = np.zeros(model.n_core)
    y[:model.n_d] = 1e-2 * rng.standard_normal(model.n_d)          # gross slip: hold lost
    start = model.initial_gauge()
    slip = model.evaluate(y, 100.0, 1.0, start)
    assert slip.drift.size == 2 and slip.state.seen.shape[1] == 2 and start.seen.shape[1] == 0
    pinned, added = slip.state.pin_seen()
    assert added and pinned.pinned.shape[1] == 2 and pinned.seen.shape[1] == 0
    assert not pinned.pin_seen()[1]                                # nothing new
    held = model.evaluate(1e-9 * y, 100.0, 1.0, slip.state)
    after = model.accepted(held.state, np.zeros(model.n_core), held)
    assert held.drift.size == 0 and after.pinned.shape[1] == 0 and after.seen.shape[1] == 0


@pytest.mark.parametrize("tilt, gauged", [(0.004, True), (0.05, False)])
def test_soft_hold_below_one_percent_counts_as_free(tilt, gauged):
    """Free mass whose motion also presses on the contact normal with a small ``tilt`` (the
    wedge effect of a tilted contact normal): in gross slip only the normal spring holds it, at
    about ``tilt`` of the stiffness scale. Below ``gauge_tol`` (1 %) that soft hold counts as
    free and the direction is gauged; above it, and with the former 1e-9, it stays held."""
    from ringdamper.nonlinear.contact.friction import FrictionContacts
    from ringdamper.nonlinear.harmonic_balance.condensed import CondensedHBM
    from ringdamper.nonlinear.harmonic_balance.structure import Structure

    M = np.diag([1.0, 0.3])
    K = np.array([[4e4, 0.0], [0.0, 0.0]])
    B = np.array([[0.0, tilt], [-1.0, 1.0], [0.0, 0.0]])
    e = np.array([1.0, 0.0])
    st = Structure.real(M, K, B, e, e, H=2)
    c = FrictionContacts(kn=3e4, kt=3e4, mu=0.3, N0=50.0, gap=0.0)
    y = np.zeros(5 * 3 + 1)
    y[3 + 1] = 5e-3                                   # first-harmonic tangential slip ≫ μN0/kt
    for tol, expect in ((None, gauged), (1e-9, False)):
        model = CondensedHBM(st, c, 2, 32) if tol is None else CondensedHBM(st, c, 2, 32,
                                                                          gauge_tol=tol)
        assert model.zero_modes.size == 1
        ev = model.evaluate(y, 150.0, 2.0, model.initial_gauge())
        assert np.all(np.abs(ev.aft.tangential[0, 0]) <= 0.3 * ev.aft.normal[0] + 1e-12)
        assert (ev.drift.size == 1) == expect
