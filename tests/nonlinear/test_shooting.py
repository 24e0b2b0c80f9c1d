"""The time-domain EPMC reference (``ringdamper.nonlinear.time_domain.shooting``) against oracles, and the HBM
against it on a chain whose EPMC frequency rises with amplitude.

* Linear oracle: below the first slip the chain is the linear stuck system; shooting from a
  detuned guess (ω +2 %, ζ 1 %) must return the stuck mode's ω (RK4 phase error (ωΔt)⁴/120
  relative, 3e-9 at 256 steps: tolerance 1e-8) and the ξ that cancels RK4's amplitude decay,
  |R(iz)| = 1 − z⁶/144 per step (z = ωΔt), i.e. ξ/ω = z⁵/72 (1.2e-10; 1 % tolerance).
* Jacobian: the tangent of the discrete period map against central differences (1e-6 of its
  largest entry; the map is piecewise linear in the state, smooth in ω, ξ; measured ≤ 5e-9) on a
  slipping chain and on a 3-D case whose normal load varies and vanishes (``multi_dof``).
* 1-DoF Jenkins oscillator in gross slip (a = 3 a_slip): the H = 1 describing function is not the
  periodic orbit (its ζ is 0.4 % off the shooting's), the HBM at H = 15 is (ζ within 3e-4
  relative: measured 1.2e-4, the H = 15 truncation; integrator error ≤ 5e-6 at 1024 steps).
* Rising chain (``jenkins_chain(149)``: 2 masses, 1 element, ω/ω_stuck − 1 = 9 % at the top of
  the family grid): at the first slipping amplitude and at the largest one, shooting from the
  HBM (H = 15) solution converges to ω within 1e-4 relative and ζ within 1e-4 absolute of it
  (measured 3.1e-5 and 1.6e-5; H = 7 → 15 still moves ω by 2.9e-4, so the H = 15 error is
  ~1e-4 at most), and the rise is in the time-domain answer (ω > 1.05 ω_stuck). The HBM
  solution returns to its start after one period within 2e-3 (measured ≤ 1e-3), the same
  state with the stuck frequency misses it by more than 0.2 (measured ≥ 0.37).
* Spurious branch (``jenkins_chain(179)`` at H = 3): the HBM finds a branch no other H finds
  (ω ≈ 0.6 ω_stuck, ζ ≈ 0.37). Both checks of a campaign point flag it at the first slipping
  amplitude: one period of the equation of motion from its state misses it by more than 0.2
  (measured 1.26; a true orbit ≤ 2e-3 above), and the harmonic-truncation indicator ε_H exceeds
  its threshold (measured 1.5e-2 = 50 × 3e-4; asserted > 10 ×).
"""
from functools import lru_cache

import numpy as np
import pytest

from ringdamper.nonlinear.contact.friction import FrictionContacts
from ringdamper.nonlinear.harmonic_balance.epmc import epmc, linear_limit
from ringdamper.nonlinear.indicators.truncation import THRESHOLD, highest_harmonic_fraction
from ringdamper.nonlinear.time_domain.shooting import (
    JenkinsTimeModel,
    hbm_state,
    march,
    phase_row,
    return_error,
    shoot,
    shooting_residual,
)
from ringdamper.status import Status
from ringdamper.studies.jenkins_chains import chain_grid, jenkins_chain

from .systems import cyclic_structure, describing_function, multi_dof, one_dof

RISING_SEED = 149
SPURIOUS_SEED = 179


def _stuck(st, c):
    w, Phi = st.stuck_modes(c.stuck_stiffness().ravel())
    return w[0], Phi[:, 0]


def test_linear_stuck_chain_is_periodic_at_the_stuck_frequency():
    st, c = jenkins_chain(RISING_SEED)
    w0, phi = _stuck(st, c)
    alpha = 0.3 * linear_limit(st, c, phi)
    model = JenkinsTimeModel(st, c)
    x0 = np.r_[alpha * phi, np.zeros(model.n), np.zeros(model.nx - 2 * model.n)]
    g = st.harmonics[1].B[1]                                  # the element's coordinate
    res = shoot(st, c, alpha, x0, 1.02 * w0, 0.02 * w0, g, n_steps=256)
    assert res.omega == pytest.approx(w0, rel=1e-8)
    z = 2 * np.pi / 256
    assert res.xi / res.omega == pytest.approx(z ** 5 / 72, rel=1e-2)
    assert np.allclose(res.x0[:model.n], alpha * phi, rtol=1e-7, atol=1e-9 * alpha)
    assert np.max(np.abs(res.x0[2 * model.n:])) <= 1e-12 * alpha   # stuck sliders stay put


@pytest.mark.parametrize("system, amplitude", [
    (lambda: jenkins_chain(43), lambda st, c, phi: 3.0 * linear_limit(st, c, phi)),  # both slip
    (lambda: multi_dof(H=1), lambda st, c, phi: 1e-2)],      # pair 0: |d_n| ≈ 2e-4 > N0/kn
    ids=["chain43", "multi_dof"])
def test_tangent_matches_finite_differences(system, amplitude):
    st, c = system()
    model = JenkinsTimeModel(st, c)
    w0, phi = _stuck(st, c)
    alpha = amplitude(st, c, phi)
    rng = np.random.default_rng(0)
    u = np.r_[alpha * phi, 0.3 * alpha * w0 * rng.standard_normal(model.n),
              0.01 * alpha * rng.standard_normal(model.nx - 2 * model.n), w0, 0.1 * w0]
    g = st.harmonics[1].B[1]
    _, J = shooting_residual(model, u, alpha, g, 64)
    fd = np.empty_like(J)
    for j in range(u.size):
        h = 1e-7 * max(abs(u[j]), alpha)
        up, um = u.copy(), u.copy()
        up[j] += h
        um[j] -= h
        fd[:, j] = (shooting_residual(model, up, alpha, g, 64, False)[0]
                    - shooting_residual(model, um, alpha, g, 64, False)[0]) / (2 * h)
    assert np.max(np.abs(J - fd)) <= 1e-6 * np.max(np.abs(J))


def test_one_dof_gross_slip_is_the_converged_hbm_not_the_describing_function():
    m, kt, mu, N = 2.0, 50.0, 0.3, 10.0
    a = 3.0 * mu * N / kt
    st, c = one_dof(H=15)
    bb = epmc(st, c, np.sqrt(m) * np.array([0.5 * a, a]), H=15, nt=1024, tol=1e-10)
    assert np.all(bb.status == Status.CONVERGED)
    x0, omega, xi = hbm_state(bb, c, 1)
    res = shoot(st, c, np.sqrt(m) * a, x0, omega, xi, phase_row(bb), n_steps=1024)
    _, zeta_df = describing_function(a, m=m, kt=kt, mu=mu, N=N)
    assert abs(res.zeta / bb.zeta[1] - 1) <= 3e-4
    assert abs(res.omega / bb.omega[1] - 1) <= 3e-5
    assert abs(res.zeta / zeta_df - 1) >= 2e-3


@lru_cache(maxsize=1)
def rising_backbone():
    st, c = jenkins_chain(RISING_SEED, H=15)
    return st, c, epmc(st, c, chain_grid(st, c), H=15, nt=1024, tol=1e-10)


@pytest.mark.parametrize("i", [2, 5], ids=["first_slip", "largest"])
def test_time_domain_confirms_the_rising_epmc_frequency(i):
    st, c, bb = rising_backbone()
    assert bb.status[i] == Status.CONVERGED
    w_stuck = _stuck(st, c)[0]
    x0, omega, xi = hbm_state(bb, c, i)
    res = shoot(st, c, bb.alpha[i], x0, omega, xi, phase_row(bb), n_steps=1024)
    assert abs(res.omega / omega - 1) <= 1e-4
    assert abs(res.zeta - bb.zeta[i]) <= 1e-4
    assert res.omega > 1.05 * w_stuck
    assert return_error(st, c, x0, omega, xi, 1024) <= 2e-3
    assert return_error(st, c, x0, w_stuck, xi, 1024) >= 0.2


def test_spurious_low_harmonic_branch_is_flagged():
    st, c = jenkins_chain(SPURIOUS_SEED, H=3)
    alpha = chain_grid(st, c, n=16)
    bb = epmc(st, c, alpha, H=3, nt=128, tol=1e-8)
    i = 4                                                # first slipping amplitude
    w_stuck = _stuck(st, c)[0]
    assert bb.status[i] == Status.CONVERGED and bb.omega[i] < 0.75 * w_stuck     # the odd branch
    x0, omega, xi = hbm_state(bb, c, i)
    assert return_error(st, c, x0, omega, xi, 1024) >= 0.2
    assert highest_harmonic_fraction(bb.model.modal, bb.eta, bb.omega)[i] > 10 * THRESHOLD


def test_bad_input_is_refused():
    st, c = jenkins_chain(RISING_SEED)
    model = JenkinsTimeModel(st, c)
    with pytest.raises(ValueError, match="n_steps"):
        march(model, np.zeros(model.nx), 1.0, 0.0, 4)
    with pytest.raises(ValueError, match="omega"):
        march(model, np.zeros(model.nx), -1.0, 0.0, 64)
    with pytest.raises(ValueError, match="alpha"):
        shoot(st, c, 0.0, np.zeros(model.nx), 1.0, 0.0, np.ones(model.n))
    with pytest.raises(ValueError, match="law"):
        JenkinsTimeModel(st, FrictionContacts(kn=1.0, kt=10.0, mu=1.0, N0=1.0, gap=0.0,
                                              law="coulomb"))
    with pytest.raises(ValueError, match="non-cyclic"):
        JenkinsTimeModel(*cyclic_structure(H=1)[:2])
