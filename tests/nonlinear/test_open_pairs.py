"""dNNM of a structure whose contact pairs are open at rest and close at amplitude.

A mass m on a spring k between two symmetric stops: pair 0 (normal +x) and pair 1 (normal −x),
each separated by the gap g at rest (the static state of a ring with a clearance). The stops carry
no preload, so the motion is linear (ω = √(k/m), ζ = 0) until the amplitude a = α/√m reaches g;
beyond, each stop is the unilateral spring of ``test_aft_oracles.test_unilateral_spring_with_gap``,
whose first-harmonic force is kn a/π (θ − sin θ cos θ), θ = arccos(g/a); by symmetry the mean
forces cancel, so the H = 1 backbone is ω² = (k + 2 kn (θ − sin θ cos θ)/π) / m, still without
damping (the tangential motion is zero). The AFT error of the kink is O(Nt⁻²): Nt = 2¹² gives
≈ 1e-6 relative on ω.
"""
import numpy as np
import pytest

from ringdamper.nonlinear.contact.friction import FrictionContacts
from ringdamper.nonlinear.harmonic_balance.epmc import epmc
from ringdamper.nonlinear.harmonic_balance.structure import Structure
from ringdamper.status import Status

M, K, KN, GAP = 2.0, 100.0, 400.0, 1.0e-3


# epmc.linear_limit divides mu N0 = 0 by kt |d_t| = 0 for these pairs without preload nor tangential
# motion (0/0 -> NaN, then discarded: only preloaded pairs can slip); the start it finds is g / |d_n|.
@pytest.mark.filterwarnings("ignore:invalid value encountered in divide:RuntimeWarning")
def test_pairs_open_at_rest_close_at_amplitude():
    B = np.array([[1.0], [0.0], [0.0], [-1.0], [0.0], [0.0]])       # (d_n, t1, t2) of both pairs
    st = Structure.real(np.array([[M]]), np.array([[K]]), B, np.array([1.0]), np.array([1.0]), H=1)
    two = np.ones(2)
    contacts = FrictionContacts(kn=KN * two, kt=0.5 * KN * two, mu=0.3 * two, N0=0.0 * two, gap=GAP * two)
    a = GAP * np.array([0.3, 0.6, 0.9, 1.05, 1.3, 2.0, 4.0, 10.0])
    bb = epmc(st, contacts, np.sqrt(M) * a, H=1, nt=2 ** 12, tol=1e-12)
    assert np.all(bb.status == Status.CONVERGED)
    theta = np.arccos(np.minimum(GAP / a, 1.0))
    omega = np.sqrt((K + 2 * KN * (theta - np.sin(theta) * np.cos(theta)) / np.pi) / M)
    open_ = a < GAP
    assert np.all(bb.omega[open_] == np.sqrt(K / M)) or np.max(np.abs(bb.omega[open_] / np.sqrt(K / M) - 1)) <= 1e-12
    assert np.max(np.abs(bb.omega / omega - 1)) <= 5e-6               # AFT kink error, Nt = 4096
    assert bb.omega[-1] > 1.5 * np.sqrt(K / M)                        # the stops did close
    assert np.max(np.abs(bb.zeta)) <= 1e-12                           # no slip, no dissipation
