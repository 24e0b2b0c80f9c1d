"""The separation indicator of the last-point study against closed forms, and its onset read-out."""
import numpy as np
import pytest
import xarray as xr

from ringdamper.nonlinear.epmc import epmc
from ringdamper.nonlinear.friction import FrictionContacts
from ringdamper.nonlinear.structure import Structure
from ringdamper.studies.last_point import normal_force_ratio, onset_of_separation


def test_normal_force_ratio_of_a_stuck_pair_is_one_minus_kn_amplitude_over_preload():
    """One mass on a spring, pressed by a preloaded pair (normal spring kn along its motion,
    friction never engaged: μ large). While the pair stays closed the EPMC is the linear mode
    (ω² = (k + kn)/m), the normal displacement is a cosine of amplitude a = α/√m, so
    min_t N/N0 = 1 − kn a / N0 exactly, down to the amplitude where it reaches 0."""
    m, k, kn, n0 = 2.0, 3.0, 5.0, 0.7
    B = np.array([[1.0], [0.0], [0.0]])                   # the mass moves along the pair's normal
    structure = Structure.real(np.array([[m]]), np.array([[k]]), B, response=np.array([1.0]),
                               force=np.array([1.0]), H=3)
    contacts = FrictionContacts(kn=[kn], kt=[kn], mu=100.0, N0=[n0], gap=0.0)
    a_open = n0 / kn                                      # normal amplitude at lift-off
    alpha = np.sqrt(m) * a_open * np.array([0.2, 0.5, 0.9])
    bb = epmc(structure, contacts, alpha, H=3, tol=1e-10)
    assert np.all(bb.status == 0)
    assert bb.omega == pytest.approx(np.sqrt((k + kn) / m), rel=1e-8)
    ratio = normal_force_ratio(bb, contacts)
    assert ratio[:, 0] == pytest.approx(1 - kn * (alpha / np.sqrt(m)) / n0, abs=1e-8)


def test_onset_is_read_where_the_ratio_crosses_zero():
    alpha = np.array([1.0, 2.0, 4.0, 8.0])
    ds = xr.Dataset({"normal_force_ratio_min": ("amplitude", [0.9, 0.4, -0.4, -1.0])},
                    coords={"amplitude": alpha})
    assert onset_of_separation(ds) == pytest.approx(np.sqrt(2.0 * 4.0))   # midway in log α
    ds["normal_force_ratio_min"][:] = [0.9, 0.8, 0.7, 0.6]
    assert np.isnan(onset_of_separation(ds))
