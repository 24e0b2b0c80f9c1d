"""Randomised family for the continuation drivers (``natural_then_arclength`` with its
``arclength`` part): 200 seeded spring–mass chains with Jenkins elements (``ringdamper.studies.jenkins_chains``:
1–5 masses, 1–3 elements, strong, non-proportional friction whose EPMC backbones fold in α, often
twice, and turn at stick–slip corners). Every backbone traced with the default steps must be the
one traced with tiny steps (maximum step 0.05 instead of 0.5, nominal tangent turn 0.05 instead
of 0.1 rad): same status at every grid amplitude and, where converged, the same ω (relative 1e-4),
ζ (absolute 1e-4) and contact-state norm (relative 1e-3). A jump to another branch changes these
by 1e-2 or more; the solver tolerance leaves about 1e-5. Runs that stop are allowed only with a
status, identically in both, and on at most 3 % of the family.
"""
import dataclasses
from functools import lru_cache

import numpy as np
import pytest

from ringdamper.nonlinear.harmonic_balance import epmc as epmc_module
from ringdamper.nonlinear.harmonic_balance.epmc import epmc
from ringdamper.nonlinear.solvers import newton
from ringdamper.nonlinear.solvers.continuation import StepControl
from ringdamper.status import Status
from ringdamper.studies.jenkins_chains import ISSUE_GRID, OPTIONS, SEEDS, chain_grid, issue_chain, jenkins_chain

TINY = StepControl(initial=0.05, minimum=1e-4, maximum=0.05, turn=0.05)


def state_norm(bb):
    return np.linalg.norm(bb.d.reshape(len(bb.alpha), -1), axis=1)


def branch_difference(a, b) -> str:
    """Why the backbones ``a`` and ``b`` on the same grid are not the same branch ("" if they
    are)."""
    if not np.array_equal(a.status, b.status):
        return f"statuses {a.status} and {b.status}"
    ok = a.status == Status.CONVERGED
    d_omega = np.max(np.abs(a.omega - b.omega)[ok] / b.omega[ok], initial=0.0)
    d_zeta = np.max(np.abs(a.zeta - b.zeta)[ok], initial=0.0)
    d_state = np.max((np.abs(state_norm(a) - state_norm(b)) / state_norm(b))[ok], initial=0.0)
    if d_omega > 1e-4 or d_zeta > 1e-4 or d_state > 1e-3:
        return f"dω/ω {d_omega:.2e}, dζ {d_zeta:.2e}, d|state| {d_state:.2e}"
    return ""


def test_default_steps_trace_the_tiny_step_branch_on_200_chains():
    jumps, stopped = [], []
    for seed in SEEDS:
        st, c = jenkins_chain(seed)
        alpha = chain_grid(st, c)
        default = epmc(st, c, alpha, **OPTIONS)
        reference = epmc(st, c, alpha, steps=TINY, **OPTIONS)
        why = branch_difference(default, reference)
        if why:
            jumps.append(f"seed {seed}: {why}")
        elif np.any(default.status != Status.CONVERGED):
            stopped.append(seed)
    assert not jumps, "\n".join(jumps)
    assert len(stopped) <= 0.03 * len(SEEDS), stopped


@lru_cache(maxsize=1)
def issue_reference():
    st, c = issue_chain()
    return epmc(st, c, ISSUE_GRID, H=1, nt=128, tol=1e-8, steps=TINY)


@pytest.mark.parametrize("steps", [None, StepControl(0.05, 1e-4, 0.05), StepControl(0.01, 1e-4, 0.01),
                                   StepControl(0.5, 1e-4, 2.0)],
                         ids=["default", "max0.05", "max0.01", "max2"])
def test_every_step_setting_gives_the_same_branch(steps):
    """The chain that jumped: every step setting reaches every grid amplitude on the branch that
    folds twice in α (up to log α ≈ −0.10, back to −0.22, up again), the one traced with tiny
    steps."""
    st, c = issue_chain()
    alpha = ISSUE_GRID
    reference = issue_reference()
    bb = epmc(st, c, alpha, H=1, nt=128, tol=1e-8, steps=steps)
    assert np.all(reference.status == Status.CONVERGED)
    assert branch_difference(bb, reference) == ""
    a = bb.branch[:, 0]
    assert a.min() >= alpha[0] * (1 - 1e-12)                      # never walked back
    assert np.any(np.diff(a) < 0)                                   # the folds were followed
    assert bb.omega[6] == pytest.approx(0.6835, abs=1e-4)           # past the folds, slipping


@pytest.mark.parametrize("seed", [1, 3, 5, 19, 28])
def test_step_settings_agree_on_folding_chains(seed):
    """Chains of the family whose backbones fold (and stopped the old driver): a large and a
    small maximum step give the branch of the default steps."""
    st, c = jenkins_chain(seed)
    alpha = chain_grid(st, c)
    default = epmc(st, c, alpha, **OPTIONS)
    assert np.all(default.status == Status.CONVERGED)
    for steps in (StepControl(0.5, 1e-4, 2.0), StepControl(0.02, 1e-4, 0.02)):
        assert branch_difference(epmc(st, c, alpha, steps=steps, **OPTIONS), default) == ""


def test_arclength_refuses_a_parallel_branch_at_every_step_size():
    """``r(z, s) = z − 10·[s > 0.3]``: two parallel branches (z = 0, z = 10) with nothing joining
    them. A corrector past s = 0.3 lands on the other one, with both end tangents parallel to the
    chord's direction of travel only in s: the chord–tangent test rejects it at every step down to
    the minimum, and the run stops there with a status instead of switching."""
    from ringdamper.nonlinear.solvers.continuation import CurveFunctions, arclength
    from ringdamper.nonlinear.solvers.jacobian import Evaluation

    def fun(x, jac):
        r = np.array([x[0] - 10.0 * (x[1] > 0.3)])
        return Evaluation(r, np.array([[1.0, 0.0]]) if jac else None, None, 1, None)

    run = arclength(CurveFunctions(fun, stop=lambda x: x[1] > 1.0), np.zeros(2), np.array([0.0, 1.0]),
                    np.ones(2), StepControl(0.25, 1e-4, 0.5, tol=1e-12, max_iter=5, max_points=100))
    assert run.status == Status.NO_CONVERGENCE and "jumped" in run.reason
    assert all(p.z[0] == 0.0 for p in run.points)
    assert 0.3 - 1e-3 < run.points[-1].z[1] <= 0.3


@pytest.mark.parametrize("kw, field", [(dict(initial=1e-5, minimum=1e-4, maximum=0.5), "minimum"),
                                       (dict(initial=0.2, minimum=1e-4, maximum=1e-5), "maximum"),
                                       (dict(initial=0.2, minimum=1e-4, maximum=0.5, turn=1.0), "turn"),
                                       (dict(initial=0.2, minimum=1e-4, maximum=0.5, corrector=0), "corrector"),
                                       (dict(initial=0.2, minimum=1e-4, maximum=0.5, give_up_damping=1.0),
                                        "give_up_damping")])
def test_step_control_refuses_bad_settings(kw, field):
    with pytest.raises(ValueError, match=field):
        StepControl(**kw)


@pytest.mark.parametrize("seed", [2, 45])
def test_fail_fast_correctors_keep_the_branch_with_fewer_factorisations(seed, monkeypatch):
    """A corrector still unconverged after ``StepControl.corrector`` fresh Jacobians, or whose damped
    Newton step needs damping at or below ``StepControl.give_up_damping``, fails its step, which is
    halved, instead of running on to ``max_iter`` (20). On chains of the family whose correctors fail
    on the way, the EPMC's default steps (both rules) trace the backbone of the same steps without them, value for value
    (without rigid-body modes to pin, a failed corrector leaves nothing behind), with fewer LU
    factorisations."""
    count = [0]
    factorize = newton.Factorization.__init__

    def counted(self, *args, **kwargs):
        count[0] += 1
        factorize(self, *args, **kwargs)

    monkeypatch.setattr(newton.Factorization, "__init__", counted)
    st, c = jenkins_chain(seed)
    alpha = chain_grid(st, c)
    runs = {}
    for limit in (True, False):
        count[0] = 0
        steps = epmc_module.default_steps()
        if not limit:
            steps = dataclasses.replace(steps, corrector=None, give_up_damping=None)
        bb = epmc(st, c, alpha, steps=steps, **OPTIONS)
        runs[limit] = bb, count[0]
    (fast, n_fast), (full, n_full) = runs[True], runs[False]
    assert fast.status.tolist() == full.status.tolist()
    ok = fast.status == Status.CONVERGED
    assert ok.sum() >= 5
    np.testing.assert_allclose(fast.omega[ok], full.omega[ok], rtol=1e-12)
    np.testing.assert_allclose(fast.zeta[ok], full.zeta[ok], rtol=1e-10, atol=1e-14)
    assert n_fast < 0.9 * n_full
