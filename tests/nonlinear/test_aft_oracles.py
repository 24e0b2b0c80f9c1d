"""docs/design.md §7 contact oracles through the AFT, to 1e-6 relative.

Quantities that the sampled AFT reproduces exactly are checked at machine precision; those with a
kink inside a sampling interval converge as O(Nt⁻²): their error is shown to shrink at that rate
and the Nt used for the 1e-6 check is the smallest power of two that meets it.
"""
import numpy as np
import pytest

from ringdamper.nonlinear.contact.friction import FrictionContacts, contact_aft, dissipated_energy
from ringdamper.nonlinear.fourier import Fourier

KT, MU, N0, KN = 2.0e4, 0.3, 50.0, 1.0e5
A_S = MU * N0 / KT


def jenkins(a, nt, law="jenkins", circle=False, H=1):
    f = Fourier(H, nt)
    c = FrictionContacts(kn=KN, kt=KT, mu=MU, N0=N0, gap=0.0, law=law)
    d = np.zeros((1, 3, f.C))
    d[0, 1, 1] = a
    if circle:
        d[0, 2, 2] = a
    lam = contact_aft(c, f, d, jacobian=False).lam
    return lam, dissipated_energy(d, lam)[0]


def jenkins_oracle(a):
    beta = np.arccos(1 - 2 * A_S / a)
    return KT / np.pi * (beta - 0.5 * np.sin(2 * beta)), 4 * MU * N0 * (a - A_S)


def test_jenkins_stuck_is_exactly_linear():
    for a in (0.3 * A_S, A_S):
        lam, energy = jenkins(a, 64, H=3)
        assert lam[0, 1, 1] == pytest.approx(KT * a, rel=1e-12)  # DFT round-off ≲ Nt·eps
        assert np.max(np.abs(np.delete(lam[0, 1], 1))) <= 1e-12 * KT * a
        assert abs(energy) <= 1e-12 * MU * N0 * A_S


@pytest.mark.parametrize("ratio", [1.3, 3.0, 20.0])
def test_jenkins_slip_stiffness_and_energy(ratio):
    a = ratio * A_S
    k_ref, e_ref = jenkins_oracle(a)
    errors = []
    for nt in (1024, 4096):
        lam, energy = jenkins(a, nt)
        errors.append(max(abs(lam[0, 1, 1] / (k_ref * a) - 1), abs(energy / e_ref - 1)))
    assert errors[1] < errors[0] / 8 or errors[1] < 1e-9          # O(Nt^-2) convergence
    lam, energy = jenkins(a, 16384)
    assert lam[0, 1, 1] == pytest.approx(k_ref * a, rel=1e-6)
    assert energy == pytest.approx(e_ref, rel=1e-6)


def test_two_jenkins_on_circle():
    r = 4.0 * A_S
    _, e1 = jenkins(r, 4096, circle=True)
    _, e2 = jenkins(r, 16384, circle=True)
    ref = 8 * MU * N0 * (r - A_S)
    assert abs(e2 / ref - 1) < abs(e1 / ref - 1) / 8 or abs(e2 / ref - 1) < 1e-9
    assert e2 == pytest.approx(ref, rel=1e-6)


def test_isotropic_coulomb_on_circle():
    r = 3.0 * A_S
    ref = 2 * np.pi * MU * N0 * np.sqrt(r * r - A_S * A_S)
    errs = [abs(jenkins(r, nt, law="coulomb", circle=True)[1] / ref - 1) for nt in (256, 1024)]
    assert errs[1] < errs[0] / 8                                  # second-order tractrix march
    _, energy = jenkins(r, 4096, law="coulomb", circle=True)
    assert energy == pytest.approx(ref, rel=1e-6)


def test_unilateral_spring_with_gap():
    a, g = 1.0e-3, 0.4e-3
    theta = np.arccos(g / a)
    mean = KN / np.pi * (a * np.sin(theta) - g * theta)
    first = KN * a / np.pi * (theta - np.sin(theta) * np.cos(theta))
    c = FrictionContacts(kn=KN, kt=KT, mu=MU, N0=0.0, gap=g)
    errs = []
    for nt in (1024, 4096, 16384):
        f = Fourier(3, nt)
        d = np.zeros((1, 3, f.C))
        d[0, 0, 1] = a
        lam = contact_aft(c, f, d, jacobian=False).lam[0, 0]
        errs.append(max(abs(lam[0] / mean - 1), abs(lam[1] / first - 1)))
    assert errs[2] < errs[0] / 16                                  # ~O(Nt^-2), oscillating
    assert errs[2] < 1e-6


def test_separation_erases_memory():
    """A pair that opens once per cycle carries no tangential force while open and restarts
    from zero force (slider at d) when it closes."""
    f = Fourier(1, 256)
    c = FrictionContacts(kn=KN, kt=KT, mu=MU, N0=N0, gap=0.0)
    d = np.zeros((1, 3, f.C))
    d[0, 0, 1] = 2 * N0 / KN                                        # opens around τ = π
    d[0, 1, 2] = 0.5 * A_S                                          # small tangential motion
    res = contact_aft(c, f, d, jacobian=False)
    open_ = res.normal[0] == 0
    assert open_.any() and (~open_).any()
    assert np.all(res.tangential[0, :, open_] == 0)
    k = np.flatnonzero(open_)[-1] + 1                               # first closed sample after
    dt = f.synth(d[0, 1])
    assert res.tangential[0, 0, k % f.nt] == pytest.approx(0.0, abs=KT * abs(dt[k % f.nt]
                                                                          - dt[k - 1]) * 1.0001)


def test_stuck_pair_keeps_the_projected_static_state_whatever_the_period_start():
    """The march starts from the static slider state (zero). A pair whose motion leaves zero
    outside its stick band ``[max(d − r), min(d + r)]`` is pushed to the nearest edge and then
    sticks: the periodic force is the same whichever sample the period starts at (the phase of
    the solution is arbitrary), and equals ``kt (d − w*)`` with ``w* = clip(0, band)``."""
    f = Fourier(2, 128)
    c = FrictionContacts(kn=KN, kt=KT, mu=MU, N0=N0, gap=0.0)
    d = np.zeros((1, 3, f.C))
    d[0, 1, 0] = 3.0 * A_S                                          # DC offset beyond the band
    d[0, 1, 1], d[0, 1, 4] = 0.4 * A_S, 0.2 * A_S                   # sticking oscillation
    dt = f.synth(d[0, 1])
    r = MU * N0 / KT
    lo, hi = np.max(dt - r), np.min(dt + r)
    assert lo < hi and not lo <= 0.0 <= hi                          # stuck, zero outside band
    expected = KT * (dt - np.clip(0.0, lo, hi))
    base = contact_aft(c, f, d, jacobian=False).tangential[0, 0]
    assert np.allclose(base, expected, rtol=0, atol=1e-12 * KT * A_S)
    for shift in (17, 64, 101):                                     # start the period elsewhere
        ds = d.copy()
        ds[0, 1] = f.analyse(np.roll(dt, -shift))
        shifted = contact_aft(c, f, ds, jacobian=False).tangential[0, 0]
        assert np.allclose(shifted, np.roll(base, -shift), rtol=0, atol=1e-9 * KT * A_S)
