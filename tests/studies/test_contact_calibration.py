"""Contact calibration (docs/calibration.md): objective, plausible ranges, a physical check."""
import numpy as np
import pytest

from ringdamper.config import load_config
from ringdamper.studies.contact_calibration.metrics import (
    PAPER_TARGET,
    SHAPE_PENALTY,
    Metrics,
    backbone_metrics,
    objective,
)
from ringdamper.studies.contact_calibration.trial import PLAUSIBLE, contact_section, in_plausible_range


def _metrics(**kw):
    base = dict(zeta_max=PAPER_TARGET["zeta_max"], q_at_zeta_max=PAPER_TARGET["q_at_zeta_max"],
                drop_at_zeta_max=PAPER_TARGET["drop_at_zeta_max"], drop_final=0.005, max_rise=0.0,
                q_onset=3e-5, n_peaks=1, peak_inside=True, usable_fraction=1.0, status_counts=[36])
    base.update(kw)
    return Metrics(**base)


def test_objective_is_the_documented_weighted_log_error():
    assert PAPER_TARGET["drop_at_zeta_max"] == pytest.approx((2.195 - 2.187) / 2.195)
    assert objective(_metrics()) == pytest.approx(0.0, abs=1e-15)
    # a factor e on any one quantity costs 1, factors multiply into a sum of squared logs
    e = np.e
    assert objective(_metrics(zeta_max=e * PAPER_TARGET["zeta_max"])) == pytest.approx(1.0)
    assert objective(_metrics(q_at_zeta_max=PAPER_TARGET["q_at_zeta_max"] / e)) == pytest.approx(1.0)
    m = _metrics(zeta_max=2 * PAPER_TARGET["zeta_max"],
                 drop_at_zeta_max=0.5 * PAPER_TARGET["drop_at_zeta_max"])
    assert objective(m) == pytest.approx(2 * np.log(2.0) ** 2)
    # shape rules: frequency rising, peak at the end of the grid, failed points
    assert objective(_metrics(max_rise=1e-3)) == pytest.approx(SHAPE_PENALTY)
    assert objective(_metrics(peak_inside=False, usable_fraction=0.5)) == pytest.approx(2 * SHAPE_PENALTY)
    assert objective(_metrics(zeta_max=float("nan"))) == float("inf")


def test_configured_contact_lies_in_the_plausible_ranges():
    contact = load_config()["contact"]
    assert in_plausible_range(contact)
    lo, hi = PLAUSIBLE["kt_over_kn"]
    assert lo <= contact["tangential_stiffness_per_area"] / contact["normal_stiffness_per_area"] <= hi
    assert not in_plausible_range(contact_section(1.5, 1e11, 0.8))      # mu out of range
    assert not in_plausible_range(contact_section(0.5, 1e14, 0.8))      # stiffness out of range
    assert not in_plausible_range(contact_section(0.5, 1e11, 0.1))      # kt/kn out of range


def test_metrics_peak_refinement_on_a_known_curve():
    q = np.geomspace(1e-6, 1e-3, 31)
    zeta = 2e-3 * np.exp(-0.5 * (np.log(q / 1.7e-4) / 0.6) ** 2)          # peak 0.2 % at 0.17 mm
    omega = 1000.0 * (1 - 4e-3 * zeta / 2e-3 * (q > 1.7e-4) - 4e-3 * zeta / 2e-3 * (q <= 1.7e-4))
    m = backbone_metrics(q, omega, zeta, np.zeros(31, int), 1000.0, q_max=1e-3)
    assert m.zeta_max == pytest.approx(2e-3, rel=1e-2)
    assert m.q_at_zeta_max == pytest.approx(1.7e-4, rel=2e-2)
    assert m.peak_inside and m.n_peaks == 1 and m.usable_fraction == 1.0


def _one_dof_backbone(mu, alpha):
    """1-DoF oscillator with one preloaded Jenkins element (docs/design.md §7 oracle system)."""
    from ringdamper.nonlinear.contact.friction import FrictionContacts
    from ringdamper.nonlinear.harmonic_balance.eebm import eebm
    from ringdamper.nonlinear.harmonic_balance.epmc import epmc
    from ringdamper.nonlinear.harmonic_balance.structure import Structure

    m, k, kt, N = 2.0, 100.0, 50.0, 10.0
    B = np.array([[0.0], [1.0], [0.0]])
    st = Structure.real(np.array([[m]]), np.array([[k]]), B, np.array([1.0]), np.array([1.0]), H=1)
    contacts = FrictionContacts(kn=1e3, kt=kt, mu=mu, N0=N, gap=0.0)
    bb = epmc(st, contacts, alpha, H=1, nt=64)
    res = eebm(bb)
    w_stuck = np.sqrt((k + kt) / m)
    return backbone_metrics(res.q_res_peak, bb.omega, bb.zeta, bb.status, w_stuck, q_max=np.inf)


def test_slip_onset_and_damping_peak_scale_with_mu():
    """Lowering μ moves the slip onset and the damping peak to smaller amplitude in proportion
    (onset a_s = μ N0 / kt) and leaves the peak damping unchanged (ζ depends on a / a_s only)."""
    alpha = np.geomspace(0.02, 3.0, 90)
    hi, lo = _one_dof_backbone(0.3, alpha), _one_dof_backbone(0.15, alpha)
    assert lo.q_onset / hi.q_onset == pytest.approx(0.5, rel=0.06)       # grid-limited (ratio 1.06)
    assert lo.q_at_zeta_max / hi.q_at_zeta_max == pytest.approx(0.5, rel=0.02)
    assert lo.zeta_max == pytest.approx(hi.zeta_max, rel=0.01)
    # onset above the stick limit a_s = mu N / kt (displacement of the 1-DoF response)
    assert 0.3 * 10.0 / 50.0 <= hi.q_onset <= 1.1 * 0.3 * 10.0 / 50.0 * 1.06
