"""Step control of the forced responses (:data:`ringdamper.nonlinear.harmonic_balance.frf.FORCED_STEPS`).

Oracle: the same forced response traced with small steps (nominal tangent turn 0.1 rad, maximum
step 0.1). The default steps must give the same refined peak (amplitude and frequency to 1e-6
relative) and stay on the same branch (every point on the small-step curve), in a bounded number
of points: a point count is a property of the step control, not a timing.
"""
import numpy as np
import pytest

from ringdamper.nonlinear.harmonic_balance.eebm import eebm
from ringdamper.nonlinear.harmonic_balance.epmc import epmc, linear_limit
from ringdamper.nonlinear.harmonic_balance.frf import forced_response, resonance_peak
from ringdamper.nonlinear.harmonic_balance.response import response_harmonics
from ringdamper.nonlinear.solvers.continuation import StepControl
from ringdamper.nonlinear.solvers.newton import newton
from ringdamper.status import Status

from .systems import cyclic_structure

SMALL_STEPS = StepControl(initial=0.02, minimum=1e-6, maximum=0.1, turn=0.1)


@pytest.fixture(scope="module")
def toy_curves():
    """Toy blisk + friction ring, H = 3, ζs = 1e-3, forced at the E-EBM forcing of a backbone
    point 5 times past the linear limit (pairs slipping over part of the period), ±3 % band."""
    st, c, _ = cyclic_structure(H=3)
    _, phi = st.stuck_modes(c.stuck_stiffness().ravel())
    alpha = np.array([5.0]) * linear_limit(st, c, phi[:, 0])
    res = eebm(epmc(st, c, alpha, H=3, nt=64), zeta_s=1e-3)
    gamma, w = float(res.gamma[0]), float(res.omega[0])
    curves = {}
    for name, steps in (("default", None), ("small", SMALL_STEPS)):
        frf = forced_response(st, c, gamma, 0.97 * w, 1.03 * w, H=3, nt=64, zeta_s=1e-3,
                              steps=steps, stability=False)
        assert frf.status == Status.CONVERGED
        curves[name] = frf, resonance_peak(frf)
    return curves


def test_default_steps_keep_the_peak_with_few_points(toy_curves):
    """Same refined peak to 1e-6 (measured: 5e-8 in amplitude, 1e-9 in frequency) in at most 50
    points (measured 43) where the small steps take over 200 (measured 348)."""
    frf, peak = toy_curves["default"]
    ref_frf, ref = toy_curves["small"]
    assert peak.refined and ref.refined
    assert peak.q_peak == pytest.approx(ref.q_peak, rel=1e-6)
    assert peak.omega == pytest.approx(ref.omega, rel=1e-6)
    assert len(frf.points) <= 50
    assert len(ref_frf.points) >= 200


def test_default_steps_stay_on_the_small_step_branch(toy_curves):
    """No jump: at every default point's frequency, Newton at fixed ω started from the small-step
    point nearest in ω lands on the default point (first-harmonic amplitude within 1e-6 of the
    peak; measured ≤ 1e-9). A point on another branch would stay on it."""
    frf, _ = toy_curves["default"]
    ref_frf, _ = toy_curves["small"]
    problem = frf.problem
    model = problem.model
    for p, q in zip(frf.points, frf.q_h1):
        near = ref_frf.points[int(np.argmin(np.abs(ref_frf.omega - p.z[-1])))]
        res = newton(problem.at_frequency(p.z[-1]), near.z[:-1], model.core_scale, 1e-10, 40)
        assert res.converged
        on_ref = abs(response_harmonics(model.modal, res.payload.eta)[1])
        assert on_ref == pytest.approx(q, abs=1e-6 * ref_frf.q_h1.max())
