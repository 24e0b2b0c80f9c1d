"""Continuation robustness: the dNNM continuation crosses the stick-to-slip transition
with every grid point converged and no gap or reversal in α; impossible requests end with a
recorded status, never an exception."""
from dataclasses import replace

import numpy as np
import pytest

from ringdamper.nonlinear.harmonic_balance.epmc import epmc, linear_limit
from ringdamper.nonlinear.harmonic_balance.frf import forced_response
from ringdamper.nonlinear.solvers.jacobian import Evaluation
from ringdamper.status import Status

from .systems import multi_dof, two_dof


def slip_onset(st, c):
    _, phi = st.stuck_modes(c.stuck_stiffness().ravel())
    return linear_limit(st, c, phi[:, 0])


def test_backbone_crosses_stick_slip_without_gaps():
    st, c = two_dof(H=3)
    a_slip = slip_onset(st, c)
    alpha = a_slip * np.logspace(-1, 2, 40)
    bb = epmc(st, c, alpha, H=3)
    assert np.all(bb.status == Status.CONVERGED)
    assert np.all(np.isfinite(bb.omega)) and np.all(np.isfinite(bb.zeta))
    assert np.all(np.diff(bb.branch[:, 0]) > 0)                   # no reversal in α
    assert np.all(np.isclose(alpha[:, None], bb.branch[None, :, 0], rtol=1e-12).any(1))  # hit
    stuck = alpha < a_slip
    assert np.all(np.abs(bb.zeta[stuck]) < 1e-12)
    assert np.all(bb.zeta[alpha > 1.05 * a_slip] > 0)
    assert np.all(np.diff(bb.omega) <= 1e-9 * bb.omega[0])        # softening, monotone
    # no jump: successive grid points change ω by less than the whole softening / 4
    assert np.max(np.abs(np.diff(bb.omega))) < 0.25 * (bb.omega[0] - bb.omega[-1])


def test_impossible_newton_budget_is_recorded():
    """No Newton iteration allowed: only the exact linear start converges; the first slipping
    point fails, the rest are marked unreached, all without an exception."""
    st, c = two_dof(H=1)
    alpha = slip_onset(st, c) * np.logspace(-1, 1, 6)
    bb = epmc(st, c, alpha, H=1, max_iter=0, tol=1e-14)
    k = int(np.argmax(bb.status != Status.CONVERGED))
    assert k > 0 and np.all(bb.status[:k] == Status.CONVERGED)
    assert bb.status[k] == Status.NO_CONVERGENCE and "step below minimum" in bb.reason[k]
    assert np.all(bb.status[k + 1:] == Status.NOT_REACHED)
    assert np.all(np.isnan(bb.omega[k:]))


def test_branch_point_stops_with_status():
    """The lowest mode of ``multi_dof`` meets a symmetry-breaking bifurcation (even harmonics)
    that neither natural continuation in α nor the arc-length fallback crosses: the run stops
    there with statuses."""
    st, c = multi_dof(H=3)
    from ringdamper.nonlinear.contact.friction import FrictionContacts
    c = FrictionContacts(kn=c.kn, kt=np.array([1e5, 8e4]), mu=0.3, N0=c.N0, gap=c.gap)
    bb = epmc(st, c, np.logspace(-4, -1, 25), H=3, nt=64, mode=0)
    failed = np.flatnonzero(bb.status != Status.CONVERGED)
    assert failed.size and np.all(bb.status[:failed[0]] == Status.CONVERGED)
    assert bb.status[failed[0]] == Status.NO_CONVERGENCE
    assert np.all(bb.status[failed[0] + 1:] == Status.NOT_REACHED)


def test_forced_response_failure_is_recorded():
    st, c = two_dof(H=1)
    frf = forced_response(st, c, 10.0, 100.0, 140.0, H=1, max_iter=0, tol=1e-14)
    assert frf.status == Status.NO_CONVERGENCE and frf.reason
    assert frf.omega.max() < 140.0


def test_backbone_does_not_depend_on_the_continuation_path():
    """Every evaluation marches the sliders from the static state, so a grid point is the same
    solution whatever steps led to it. Two step controls (23 and 234 accepted points) agree to
    the solver tolerance at every grid point, through stick, microslip and gross slip."""
    from ringdamper.nonlinear.solvers.continuation import StepControl

    st, c = multi_dof(H=3)
    _, phi = st.stuck_modes(c.stuck_stiffness().ravel())
    alpha = linear_limit(st, c, phi[:, 2]) * np.logspace(-0.5, 1.5, 9)
    a, b = (epmc(st, c, alpha, H=3, nt=64, tol=1e-11, mode=2,
                 steps=StepControl(initial=s0, minimum=1e-5, maximum=smax))
            for s0, smax in ((0.2, 0.5), (0.01, 0.02)))
    assert np.all(a.status == Status.CONVERGED) and np.all(b.status == Status.CONVERGED)
    assert len(b.branch) > 5 * len(a.branch)
    assert np.allclose(a.omega, b.omega, rtol=1e-10)
    assert np.allclose(a.xi, b.xi, rtol=0, atol=1e-10 * a.omega[0])
    assert np.max(a.zeta) > 1e-2                                    # friction did act


def test_points_between_grid_values_converged_loosely_leave_the_grid_points_unchanged():
    """Points between grid values only carry the predictor and the step geometry: with their
    corrector stopped at 1e-5 (and at 1e-3 of the step) instead of the run's 1e-11, every grid point
    is the same solution to the solver tolerance, through stick, microslip and gross slip; a grid
    point itself is always converged to the run's tolerance."""
    from ringdamper.nonlinear.solvers.continuation import StepControl

    tight = StepControl(initial=0.05, minimum=1e-5, maximum=0.1)
    loose = StepControl(initial=0.05, minimum=1e-5, maximum=0.1, between=1e-5)
    assert replace(loose, tol=1e-11).corrector_tolerance(0.05, on_grid=True) == 1e-11
    assert replace(loose, tol=1e-11).corrector_tolerance(0.05, on_grid=False) == 1e-5
    assert replace(loose, tol=1e-11).corrector_tolerance(1e-4, on_grid=False) == pytest.approx(1e-7)
    assert replace(tight, tol=1e-11).corrector_tolerance(0.05, on_grid=False) == 1e-11
    st, c = multi_dof(H=3)
    _, phi = st.stuck_modes(c.stuck_stiffness().ravel())
    alpha = linear_limit(st, c, phi[:, 2]) * np.logspace(-0.5, 1.5, 5)
    a, b = (epmc(st, c, alpha, H=3, nt=64, tol=1e-11, mode=2, steps=steps) for steps in (tight, loose))
    assert np.all(a.status == Status.CONVERGED) and np.all(b.status == Status.CONVERGED)
    assert len(b.branch) > 2 * alpha.size                          # points between the grid values
    assert np.max(a.zeta) > 1e-2                                    # friction did act
    np.testing.assert_allclose(b.omega, a.omega, rtol=1e-10)
    assert np.all(np.abs(b.xi - a.xi) <= 1e-10 * a.omega)


def test_arc_points_past_a_fold_are_bounded():
    """The fold of the free body below needs the arc-length part (``bb.branch`` folds back); allowed
    fewer arc-length points than it takes to reach every grid value, the continuation stops there, says
    so, and keeps every value it reached as the unbounded run has it."""
    from .systems import free_body

    st, c = free_body(H=3, normal_coupling=0.3)
    alpha = 1e-3 * np.logspace(-1.5, 0.25, 8)
    full = epmc(st, c, alpha, H=3, nt=64, tol=1e-12)
    short = epmc(st, c, alpha, H=3, nt=64, tol=1e-12, max_arc_points=3)
    reached = short.status != Status.NO_CONVERGENCE
    assert not reached.all() and "3 points reached" in short.reason[np.flatnonzero(~reached)[0]]
    kept = np.isin(short.status, (Status.CONVERGED, Status.DRIFT))
    assert kept.any() and np.array_equal(short.omega[kept], full.omega[kept])


def test_fold_in_alpha_is_passed_by_arc_length():
    """A free mass on an oscillator whose normal load follows the motion (``free_body`` with
    normal coupling): past the loss of stick the backbone folds in α (α rises, falls back by
    15 %, rises again) where natural continuation must stop. The arc-length fallback follows
    the fold; every grid point is reached, its solution satisfies the residual at its exact α,
    and it lies on the first crossing of the branch."""
    from .systems import free_body

    st, c = free_body(H=3, normal_coupling=0.3)
    alpha = 1e-3 * np.logspace(-1.5, 0.25, 8)
    bb = epmc(st, c, alpha, H=3, nt=64, tol=1e-12)
    assert np.all(np.isin(bb.status, (Status.CONVERGED, Status.DRIFT)))
    a = bb.branch[:, 0]
    assert np.any(np.diff(a) < 0)                                    # the fold was followed
    top = np.argmax(a[:np.argmax(np.diff(a) < 0) + 1])
    assert a[top] < alpha[-1] and np.min(a[top:]) < 0.9 * a[top]
    for i in (len(alpha) - 1,):                                      # the point past the fold
        z = bb.unknowns(i)
        r = bb.problem(i).fun(z, np.log(alpha[i]), False).r
        assert abs(r[-2]) < 1e-10 and np.max(np.abs(r[:-2])) < 1e-8 * np.max(np.abs(z[:-2]))
    assert bb.omega[-1] < 0.7 * bb.omega[0]                          # far along the branch


def test_jump_test_can_leave_out_unknowns_that_move_freely():
    """``r = [z0 − s, z1 − 10·[s > 0.3]]``: z0 follows s smoothly, z1 (standing for the mean
    position of a ring that lets go) jumps at s = 0.3. The jump test stops natural continuation
    there, unless ``jump_mask`` leaves z1 out; with the mask every grid value is reached."""
    from ringdamper.nonlinear.solvers.continuation import ParameterFunctions, StepControl, natural

    def fun(z, s, jac):
        r = np.array([z[0] - s, z[1] - 10.0 * (s > 0.3)])
        return Evaluation(r, np.eye(2) if jac else None, None, 2, None)

    def dfun_ds(z, s):
        return np.array([-1.0, 0.0])

    grid = np.linspace(0.0, 1.0, 6)
    steps = StepControl(0.1, 1e-4, 0.2, tol=1e-12, max_iter=5)
    plain = natural(ParameterFunctions(fun, dfun_ds, lambda z: np.ones(2)), np.zeros(2), grid, steps)
    masked = natural(ParameterFunctions(fun, dfun_ds, lambda z: np.ones(2), jump_mask=np.array([True, False])),
                     np.zeros(2), grid, steps)
    assert plain.status[2] == Status.NO_CONVERGENCE and "jumped" in plain.reason[2]
    assert np.all(masked.status == Status.CONVERGED)
    assert masked.points[-1].z == pytest.approx([1.0, 10.0])


def test_freely_moving_unknowns_do_not_set_the_arc_length(monkeypatch):
    """``r = [y³ − y − s, m − 100·y]``: an S-fold in s (at y = ±1/√3) that natural continuation
    cannot pass, and an unknown ``m`` (standing for the mean position of a ring that lets go) that
    moves 100 times faster than ``y``. Left out of the jump test by ``jump_mask``, it weighs
    ``FREE_WEIGHT`` in the arc length: the fold is followed to the same grid values on the branch
    beyond it in well under half the points that full weight takes (where ``m``'s travel, about
    400 scaled units at steps of at most 0.5, sets the steps)."""
    import ringdamper.nonlinear.solvers.continuation as continuation

    def fun(z, s, jac):
        y, m = z
        r = np.array([y ** 3 - y - s, m - 100.0 * y])
        return Evaluation(r, np.array([[3 * y ** 2 - 1, 0.0], [-100.0, 1.0]]) if jac else None, None, 2, None)

    def dfun_ds(z, s):
        return np.array([-1.0, 0.0])

    grid = np.linspace(-6.0, 6.0, 7)

    def trace():
        y0 = -2.0
        return continuation.natural_then_arclength(
            continuation.ParameterFunctions(fun, dfun_ds, lambda z: np.ones(2), jump_mask=np.array([True, False])),
            np.array([y0, 100 * y0]), grid,
            continuation.StepControl(0.2, 1e-4, 0.5, tol=1e-12, max_iter=20, max_points=400))

    assert continuation.FREE_WEIGHT < 1.0
    weighted = trace()
    monkeypatch.setattr(continuation, "FREE_WEIGHT", 1.0)
    full = trace()
    for run in (weighted, full):
        assert np.all(run.status == Status.CONVERGED)
        ys = np.array([p.z[0] for p in run.points])
        assert ys ** 3 - ys == pytest.approx(grid, abs=1e-9)
        assert np.all(ys[grid > 0.4] > 1 / np.sqrt(3))             # past the fold, on the upper branch
    assert len(weighted.branch) < 0.5 * len(full.branch)


def test_arc_length_stops_where_the_branch_turns_back_below_the_floor():
    """``r = y³ − y − s``: past the fold at s = 2/(3√3) ≈ 0.385 the branch runs back down to
    s ≈ −0.385 before the second fold takes it up again. With a floor above that (−0.2) the
    arc-length part stops at the first point below it and says so; with a floor below it (−0.5) the S
    is followed and every grid value reached, on the same points as without a floor."""
    import ringdamper.nonlinear.solvers.continuation as continuation

    def fun(z, s, jac):
        y = z[0]
        return Evaluation(np.array([y ** 3 - y - s]), np.array([[3 * y ** 2 - 1]]) if jac else None, None, 1, None)

    grid = np.linspace(-6.0, 6.0, 7)

    def trace(floor):
        return continuation.natural_then_arclength(
            continuation.ParameterFunctions(fun, lambda z, s: np.array([-1.0]), lambda z: np.ones(1)),
            np.array([-2.0]), grid, continuation.StepControl(0.2, 1e-4, 0.5, tol=1e-12, max_iter=20, max_points=400),
            floor=floor)

    free, low, high = trace(None), trace(-0.5), trace(-0.2)
    for run in (free, low):
        assert np.all(run.status == Status.CONVERGED)
    assert [p.s for p in low.branch] == [p.s for p in free.branch]
    reached = high.status == Status.CONVERGED
    np.testing.assert_array_equal(reached, grid < 0.385)
    assert "turns back (fold at s=0.38" in high.reason[np.flatnonzero(~reached)[0]]
    assert high.branch[-1].s < -0.2 < high.branch[-2].s           # stopped at the first point below
    assert len(high.branch) < len(free.branch)
