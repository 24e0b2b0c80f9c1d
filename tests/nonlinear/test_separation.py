"""The contact-separation indicator (``ringdamper.nonlinear.indicators.separation``) against closed forms.

One mass on a spring, pressed by a preloaded pair (normal spring kn along its motion, friction never
engaged: μ large). While the pair stays closed the EPMC is the linear mode (ω² = (k + kn)/m) and
the normal displacement a cosine of amplitude a = α/√m, so min_t N/N0 = 1 − kn a / N0 exactly, down
to a_open = N0/kn where it reaches 0. Above a_open the pair opens for part of the period: it is
the one lifting pair, and the stage's warning names the first amplitude where it lifts.
"""
import logging

import numpy as np
import pytest

from ringdamper.nonlinear.contact.friction import FrictionContacts
from ringdamper.nonlinear.harmonic_balance.epmc import epmc
from ringdamper.nonlinear.harmonic_balance.structure import Structure
from ringdamper.nonlinear.indicators.separation import normal_force_ratio, separation_indicators, warn_separation

M, K, KN, N0 = 2.0, 3.0, 5.0, 0.7
A_OPEN = N0 / KN                                      # normal amplitude at lift-off


def pressed_mass(alpha):
    B = np.array([[1.0], [0.0], [0.0]])               # the mass moves along the pair's normal
    structure = Structure.real(np.array([[M]]), np.array([[K]]), B, response=np.array([1.0]),
                               force=np.array([1.0]), H=3)
    contacts = FrictionContacts(kn=[KN], kt=[KN], mu=100.0, N0=[N0], gap=0.0)
    return epmc(structure, contacts, alpha, H=3, tol=1e-10), contacts


def test_normal_force_ratio_of_a_stuck_pair_is_one_minus_kn_amplitude_over_preload():
    alpha = np.sqrt(M) * A_OPEN * np.array([0.2, 0.5, 0.9])
    bb, contacts = pressed_mass(alpha)
    assert np.all(bb.status == 0)
    assert bb.omega == pytest.approx(np.sqrt((K + KN) / M), rel=1e-8)
    ratio = normal_force_ratio(bb, contacts)
    assert ratio[:, 0] == pytest.approx(1 - KN * (alpha / np.sqrt(M)) / N0, abs=1e-8)


def test_lifting_pair_is_counted_and_reported_from_its_first_amplitude(caplog):
    alpha = np.sqrt(M) * A_OPEN * np.array([0.5, 0.9, 1.5, 2.5])
    bb, contacts = pressed_mass(alpha)
    assert np.all(bb.status == 0)
    assert bb.omega[-1] < 0.99 * bb.omega[0]           # the opening pair softens the mode
    n_min, lifting = separation_indicators(bb, contacts, bb.status == 0)
    assert lifting.tolist() == [0, 0, 1, 1]
    assert n_min[:2] == pytest.approx([0.5, 0.1], abs=1e-8) and np.all(n_min[2:] < 0)
    with caplog.at_level(logging.WARNING):
        assert warn_separation(lifting, alpha, 3)
    assert f"2 amplitudes from alpha = {alpha[2]:.4g}" in caplog.text
    masked = separation_indicators(bb, contacts, np.array([True, True, True, False]))
    assert np.isnan(masked[0][3]) and np.isnan(masked[1][3])
    assert not warn_separation(lifting[:2], alpha[:2], 3)
