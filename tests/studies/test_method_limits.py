"""Where the methods fail, each limit pinned on a system with a known answer (docs/method_limits.md).

* E-EBM: on a linear oscillator its resonant amplitude is off by exactly ``√(1 − ζ²) − 1`` against
  the forced peak (so 5 % is passed at ζ = 0.312); with non-proportional friction damping (two-DoF
  chain) the error passes 5 % once ζ_tot exceeds the validity limit, and such points are flagged
  and logged.
* Harmonic truncation: where the pair of the gap family closes over part of the period, H = 1 is
  off by more than 1 % (ω or amplitude at equal forcing) against H = 9, the highest-harmonic energy
  fraction of H = 2 and 3 flags the truncation, and H = 5 (whose fraction stays below the
  threshold) is within 1 %.
"""
import logging

import numpy as np
import pytest

from ringdamper.nonlinear.harmonic_balance.eebm import ZETA_LIMIT
from ringdamper.nonlinear.indicators.truncation import THRESHOLD, warn_truncation
from ringdamper.studies.method_limits import eebm_validity as ev
from ringdamper.studies.method_limits.harmonics import FAMILIES, truncation_study, worst_error


@pytest.mark.parametrize("zeta_s", [0.1, 0.4, 0.55])
def test_eebm_on_a_linear_oscillator_is_off_by_the_exact_amount(zeta_s):
    """ζ_s is the ratio of the structure's mode (ω_r = 1); the stuck element raises the frequency
    to √2, so the damping ratio at the resonance is ζ_tot = ζ_s/√2."""
    st, c = ev.jenkins_oscillator(1.0, slip=False)
    row, = ev.compare(st, c, zeta_s, [ev.SLIP_AMPLITUDE])
    zeta = row["zeta_total"]
    assert zeta == pytest.approx(zeta_s / np.sqrt(2), rel=1e-9)
    assert row["error"] == pytest.approx(np.sqrt(1 - zeta ** 2) - 1, rel=1e-4)
    assert (abs(row["error"]) > 0.05) == (zeta > 0.312)


def test_eebm_with_friction_damping_fails_past_the_limit_and_warns(caplog):
    st, c = ev.jenkins_oscillator(3.0, dofs=2)
    with caplog.at_level(logging.WARNING, logger="ringdamper.nonlinear.harmonic_balance.eebm"):
        low, high = ev.compare(st, c, 1e-3, ev.SLIP_AMPLITUDE * np.array([1.8, 6.0]))
    assert low["zeta_total"] < ZETA_LIMIT and abs(low["error"]) < 0.05
    assert high["zeta_total"] > ZETA_LIMIT and abs(high["error"]) > 0.05
    assert any("outside its validity range" in r.message for r in caplog.records)


@pytest.fixture(scope="module")
def gap_family():
    return truncation_study(np.geomspace(0.05, 0.3, 6), families={"gap": FAMILIES["gap"]},
                            harmonics=(1, 2, 3, 5), reference_H=9).sel(family="gap")


def test_truncation_errors_grow_where_the_contact_separates(gap_family, caplog):
    worst = worst_error(gap_family)
    closing = gap_family.open_fraction.values < 0.9                   # closes over >10 % of T
    assert closing.sum() >= 5
    assert np.all(worst.sel(n_harmonics=1).values[closing] > 0.01)
    eps = gap_family.highest_harmonic_energy
    for H in (2, 3):
        assert np.all(eps.sel(n_harmonics=H).values[closing] > THRESHOLD)
    assert worst.sel(n_harmonics=3).values[closing].max() > 0.01     # flagged, and rightly so
    with caplog.at_level(logging.WARNING, logger="ringdamper.nonlinear.indicators.truncation"):
        assert warn_truncation(eps.sel(n_harmonics=2).values, gap_family.amplitude.values)
    assert "more harmonics are needed" in caplog.text
    assert np.all(eps.sel(n_harmonics=5).values < THRESHOLD)
    assert np.all(worst.sel(n_harmonics=5).values < 0.01)
