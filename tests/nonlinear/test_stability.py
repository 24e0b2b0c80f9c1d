"""Hill's method against oracles (docs/method_limits.md §4).

* Duffing oscillator ``ẍ + 2ζẋ + x + κx³ = F cos ωt`` (hardening): the branch between the two folds
  of the forced response is unstable, the rest stable. At H = 1 the oracle is analytic: with
  ``G(s) = s[(1 − ω² + ¾κs)² + (2ζω)²]`` the amplitude relation ``G(a²) = F²``, a solution is a
  saddle (unstable) exactly where ``dG/ds < 0`` (Nayfeh & Mook 1979, §4.1). At H = 3, 5 the oracle is
  the branch's own geometry: unstable where it runs back in ω (folds between neighbours left out).
* Condensing the modes far from every harmonic (large models) keeps the leading exponents.
* Linear (always stuck) friction oscillator with modal damping: every point stable, with the
  Floquet exponents' real parts exactly ``−c_r/2``.
"""
import numpy as np
import pytest

from ringdamper.nonlinear.frf import forced_response
from ringdamper.nonlinear.stability import hill_exponents, modal_hill_matrices
from ringdamper.studies.method_limits.stability import KAPPA, ZETA, duffing_frf

from .systems import multi_dof, one_dof


def test_duffing_h1_against_the_analytic_saddle_criterion():
    z, stable = duffing_frf(1)
    s, w = z[:, 1] ** 2 + z[:, 2] ** 2, z[:, -1]
    u = 1 - w ** 2 + 0.75 * KAPPA * s
    dG = u ** 2 + (2 * ZETA * w) ** 2 + 1.5 * KAPPA * s * u
    clear = np.abs(dG) > 1e-3 * np.max(np.abs(dG))          # away from the folds themselves
    assert np.any(dG[clear] < 0) and np.any(dG[clear] > 0)  # the branch has its middle part
    np.testing.assert_array_equal(stable[clear], dG[clear] > 0)


@pytest.mark.parametrize("H", [3, 5])
def test_duffing_unstable_exactly_between_the_folds(H):
    z, stable = duffing_frf(H)
    dw = np.diff(z[:, -1])
    back = (dw[:-1] < 0) & (dw[1:] < 0)             # branch running back in ω on both sides
    ahead = (dw[:-1] > 0) & (dw[1:] > 0)            # (a fold between two neighbours: neither)
    assert back.sum() > 5 and ahead.sum() > 20
    np.testing.assert_array_equal(stable[1:-1][back | ahead], ahead[back | ahead])


def test_linear_stuck_oscillator_is_stable_with_exact_decay_rates():
    st, c = one_dof(H=3, mu=100.0)                         # never slips: a linear oscillator
    zeta_s = 0.01
    w = np.sqrt(150 / 2)
    frf = forced_response(st, c, 1.0, 0.9 * w, 1.1 * w, H=3, zeta_s=zeta_s)
    assert frf.status == 0 and frf.stable.all()
    # modal damping c_r = 2 ζ_s ω_r on the structure's mode (unit modal mass): Re λ = −c_r/2
    np.testing.assert_allclose(frf.growth, -zeta_s * np.sqrt(100 / 2), rtol=1e-8)


def test_condensed_modes_leave_the_stability_unchanged():
    """6-DoF friction system with separation, forced up its first resonance: the leading Hill
    exponents with the modes above Hω condensed (band 0) match those with every mode kept."""
    st, c = multi_dof(H=3)
    frf = forced_response(st, c, 50.0, 130.0, 150.0, H=3, zeta_s=0.01, stability=False)
    assert frf.status == 0
    model = frf.problem.model
    for p in frf.points[::5]:
        w = p.z[-1]
        ev = model.evaluate(p.z[:-1], w, 0.0, True)
        full = hill_exponents(*modal_hill_matrices(model, ev, w, band=np.inf), w)
        part = hill_exponents(*modal_hill_matrices(model, ev, w, band=0.0), w)
        lead = full[np.argsort(-full.real)[:2]]
        assert np.all(np.min(np.abs(part[:, None] - lead), axis=0) <= 1e-3 * np.abs(lead))
