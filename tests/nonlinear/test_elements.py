"""Nonlinear elements on a user's structure (``ringdamper.nonlinear.contact.elements``).

Per element, through the AFT on ``u = a cos τ`` (H = 1):

* cubic spring: first harmonic ``¾ k3 a³``, exact for Nt ≥ 5 (1e-12), no dissipation;
* unilateral spring (gap g < a, θ₀ = arccos(g/a)): mean ``(k/π)(a sin θ₀ − g θ₀)``, first harmonic
  ``(2k/π)(a(θ₀/2 + sin 2θ₀/4) − g sin θ₀)``; a kink inside a sampling interval makes the error
  O(Nt⁻²): shown to shrink at that rate, then 1e-6 at Nt = 16384; no dissipation;
* 1-D Jenkins: in-phase stiffness ``kt/π (β − ½ sin 2β)`` and dissipation ``4 F_s (a − a_s)`` (the
  describing function, as for the 3-D contact), 1e-6 at Nt = 16384; and equal to the 3-D contact's
  tangential direction (kn large, no normal motion) to 1e-13 at any state;
* tanh friction with ``ε ≪ a ω``: Coulomb's describing function, first sine coefficient ``−4F/π`` and
  dissipation ``4 F a`` (1e-3, the regularisation's share ~ε/(aω));
* the analytic Jacobian, and ``∂f/∂ω`` and the velocity Jacobian ``∂f_c/∂v_c'`` of tanh friction,
  against central differences (1e-6 of the largest entry) at H = 3.

Systems: the Duffing oscillator's H = 1 backbone ``ω² = (k + ¾ k3 a²)/m`` (Newton tolerance: 1e-7);
the one-DoF Jenkins oscillator with the 1-D element and with the 3-D contact, the same backbone
(ω 1e-12, ζ 1e-14); a mass on a spring with tanh friction at H = 1 and ε ≪ aω: the frequency stays
``√(k/m)`` (1e-12) and ζ is Coulomb's describing function ``2F/(π m a ω²)`` (1e-4, measured 3e-6), and
forced at small amplitude its Hill exponent is the slow decay of the damper ``F/ε`` at rest (1e-6);
two cubic springs on one coordinate equal to one with the summed k3 (1e-10 at
Newton tolerance 1e-12: the two problems have different unknowns, so Newton stops at other iterates).
"""
import numpy as np
import pytest

from ringdamper.nonlinear.contact.elements import CubicSpring, Elements, Jenkins, TanhFriction, UnilateralSpring
from ringdamper.nonlinear.contact.friction import FrictionContacts, contact_aft, dissipated_energy
from ringdamper.nonlinear.fourier import Fourier
from ringdamper.nonlinear.harmonic_balance.epmc import epmc
from ringdamper.nonlinear.harmonic_balance.frf import forced_response
from ringdamper.nonlinear.harmonic_balance.structure import Structure
from ringdamper.status import Status

from .systems import one_dof

K3, KU, GAP, KT, FS = 40.0, 300.0, 0.2, 50.0, 3.0


def _harmonic_one(element, a, nt):
    """Force coefficients and dissipated energy of ``element`` on ``u = a cos τ`` (H = 1)."""
    fourier = Fourier(1, nt)
    u = np.zeros((1, fourier.C))
    u[0, 1] = a
    lam = element.aft(fourier, u, False)[0]
    return lam[0], dissipated_energy(u[None], lam[None])[0]


def test_cubic_spring_is_its_describing_function_exactly():
    for a in (0.1, 1.0, 7.0):
        lam, energy = _harmonic_one(CubicSpring([1.0], K3), a, 8)
        np.testing.assert_allclose(lam, [0.0, 0.75 * K3 * a ** 3, 0.0], rtol=0, atol=1e-12 * K3 * a ** 3)
        assert abs(energy) <= 1e-12 * K3 * a ** 4


def test_unilateral_spring_converges_to_its_describing_function():
    a = 1.0
    theta = np.arccos(GAP / a)
    mean = KU / np.pi * (a * np.sin(theta) - GAP * theta)
    first = 2 * KU / np.pi * (a * (theta / 2 + np.sin(2 * theta) / 4) - GAP * np.sin(theta))
    errors = []
    for nt in (1024, 4096, 16384):
        lam, energy = _harmonic_one(UnilateralSpring([1.0], KU, GAP), a, nt)
        errors.append(max(abs(lam[0] / mean - 1), abs(lam[1] / first - 1)))
        assert abs(energy) <= 1e-9 * KU * a * a
    assert errors[1] < errors[0] / 8 or errors[1] < 1e-9                 # O(Nt^-2)
    assert errors[2] <= 1e-6


def test_jenkins_element_is_its_describing_function():
    a_s, a = FS / KT, 3.0 * FS / KT
    beta = np.arccos(1 - 2 * a_s / a)
    lam, energy = _harmonic_one(Jenkins([1.0], KT, FS), a, 16384)
    assert lam[1] == pytest.approx(KT / np.pi * (beta - 0.5 * np.sin(2 * beta)) * a, rel=1e-6)
    assert energy == pytest.approx(4 * FS * (a - a_s), rel=1e-6)


def test_jenkins_element_is_the_tangential_direction_of_the_contact():
    rng = np.random.default_rng(4)
    fourier = Fourier(3, 64)
    contact = FrictionContacts(kn=1e9, kt=KT, mu=FS / 1e3, N0=1e3, gap=0.0)
    for size in (0.3, 1.0, 5.0):
        u = rng.standard_normal((1, fourier.C)) * size * FS / KT
        d = np.zeros((1, 3, fourier.C))
        d[0, 1] = u[0]
        reference = contact_aft(contact, fourier, d)
        lam, jac, _ = Jenkins([1.0], KT, FS).aft(fourier, u, True)
        np.testing.assert_allclose(lam[0], reference.lam[0, 1], rtol=0, atol=1e-13 * FS)
        np.testing.assert_allclose(jac[0, :, 0], reference.jac[0, 1, :, 1], rtol=0, atol=1e-13 * KT)


def test_tanh_friction_is_coulomb_for_a_small_regularisation():
    a, omega = 1.0, 2.0
    fourier = Fourier(1, 16384)
    u = np.zeros((1, fourier.C))
    u[0, 1] = a
    lam = TanhFriction([1.0], FS, eps=1e-4 * a * omega).aft(fourier, u, False, omega)[0]
    assert lam[0, 2] == pytest.approx(-4 * FS / np.pi, rel=1e-3)
    assert dissipated_energy(u[None], lam[None])[0] == pytest.approx(4 * FS * a, rel=1e-3)


@pytest.mark.parametrize("element", [CubicSpring([1.0], K3), UnilateralSpring([1.0], KU, GAP),
                                     Jenkins([1.0], KT, FS), TanhFriction([1.0], FS, eps=0.3)],
                         ids=["cubic", "unilateral", "jenkins", "tanh"])
def test_element_jacobian_matches_finite_differences(element):
    rng = np.random.default_rng(1)
    fourier = Fourier(3, 64)
    u = rng.standard_normal((1, fourier.C)) * 0.3
    u[0, 1] = 1.0
    omega = 1.3
    _, jac, dw = element.aft(fourier, u, True, omega)
    J = jac.reshape(fourier.C, fourier.C)
    h = 1e-7

    def force(x, w=omega):
        return element.aft(fourier, x, False, w)[0].ravel()

    fd = np.array([(force(u + h * e) - force(u - h * e)) / (2 * h) for e in np.eye(fourier.C)[:, None, :]]).T
    assert np.max(np.abs(J - fd)) <= 1e-6 * np.max(np.abs(fd))
    if element.velocity_dependent:
        fd_w = (force(u, omega + h) - force(u, omega - h)) / (2 * h)
        assert np.max(np.abs(dw.ravel() - fd_w)) <= 1e-6 * np.max(np.abs(fd_w))
        _check_velocity_jacobian(element, fourier, u, omega, h)
    else:
        assert dw is None and element.velocity_jacobian(fourier, u, omega) is None


def _check_velocity_jacobian(element, fourier, u, omega, h):
    """``∂f_c/∂v_c'`` against central differences of ``F f(E u, E v)`` in the velocity's coefficients
    ``v`` taken apart from ``u`` (at ``v`` those of ``u̇ = ω ∂u/∂τ``)."""
    v = fourier.analyse(omega * (u @ fourier.dE.T))

    def force(x):
        return fourier.analyse(element.force(fourier.synth(u), fourier.synth(x))[0]).ravel()

    Jv = element.velocity_jacobian(fourier, u, omega).reshape(fourier.C, fourier.C)
    fd = np.array([(force(v + h * e) - force(v - h * e)) / (2 * h) for e in np.eye(fourier.C)[:, None, :]]).T
    assert np.max(np.abs(Jv - fd)) <= 1e-6 * np.max(np.abs(fd))


def _one_dof(elements, H, m=2.0, k=100.0):
    return Structure.real(np.array([[m]]), np.array([[k]]), elements.B, np.array([1.0]), np.array([1.0]), H=H)


def test_duffing_backbone_at_h1_is_the_analytic_one():
    m, k = 2.0, 100.0
    elements = Elements([CubicSpring([1.0], K3)], 1)
    alpha = np.geomspace(0.01, 3.0, 10)
    bb = epmc(_one_dof(elements, 1, m, k), elements, alpha, H=1, nt=16)
    assert np.all(bb.status == Status.CONVERGED)
    a = alpha / np.sqrt(m)                                  # mass-normalised modal amplitude
    np.testing.assert_allclose(bb.omega, np.sqrt((k + 0.75 * K3 * a ** 2) / m), rtol=1e-7)
    np.testing.assert_allclose(bb.zeta, 0.0, atol=1e-14)


def test_tanh_friction_backbone_at_h1_is_coulombs_describing_function():
    m, k = 2.0, 100.0
    elements = Elements([TanhFriction([1.0], FS, eps=1e-4)], 1)
    alpha = np.geomspace(0.05, 2.0, 6)
    bb = epmc(_one_dof(elements, 1, m, k), elements, alpha, H=1, nt=1024)
    assert np.all(bb.status == Status.CONVERGED)
    w0 = np.sqrt(k / m)
    a = alpha / np.sqrt(m)
    np.testing.assert_allclose(bb.omega, w0, rtol=1e-12)
    np.testing.assert_allclose(bb.zeta, 2 * FS / (np.pi * m * a * w0 ** 2), rtol=1e-4)


def test_tanh_friction_forced_at_small_amplitude_decays_as_its_damper():
    """|u̇| ≈ 3e-4 ε: the friction is the damper c = F_s/ε = 3e4 N s/m, the oscillator overdamped; Hill's
    largest exponent is the slow root of m λ² + c λ + k (1e-6; measured 6e-8, the tanh’s cubic term)."""
    m, k = 2.0, 100.0
    elements = Elements([TanhFriction([1.0], FS, eps=1e-4)], 1)
    w0 = np.sqrt(k / m)
    frf = forced_response(_one_dof(elements, 1, m, k), elements, 1e-3, 0.9 * w0, 1.1 * w0, H=1, nt=64)
    assert frf.status == Status.CONVERGED and frf.stable.all()
    c = FS / 1e-4
    np.testing.assert_allclose(frf.growth, (-c + np.sqrt(c * c - 4 * m * k)) / (2 * m), rtol=1e-6)


def test_jenkins_element_and_contact_give_the_same_backbone():
    st, contact = one_dof(H=3)
    elements = Elements([Jenkins([1.0], kt=50.0, slip_force=0.3 * 10.0)], 1)
    alpha = np.geomspace(0.01, 1.0, 8)
    with_contact = epmc(st, contact, alpha, H=3)
    with_element = epmc(_one_dof(elements, 3), elements, alpha, H=3)
    assert np.all(with_element.status == Status.CONVERGED)
    assert np.max(with_element.zeta) > 0.05
    np.testing.assert_allclose(with_element.omega, with_contact.omega, rtol=1e-12)
    np.testing.assert_allclose(with_element.zeta, with_contact.zeta, rtol=0, atol=1e-14)


def test_elements_on_one_coordinate_add_up():
    alpha = np.geomspace(0.01, 3.0, 6)
    two = Elements([CubicSpring([1.0], 0.3 * K3), CubicSpring([1.0], 0.7 * K3)], 1)
    one = Elements([CubicSpring([1.0], K3)], 1)
    bb_two = epmc(_one_dof(two, 3), two, alpha, H=3, tol=1e-12)
    bb_one = epmc(_one_dof(one, 3), one, alpha, H=3, tol=1e-12)
    np.testing.assert_allclose(bb_two.omega, bb_one.omega, rtol=1e-10)


def test_element_inputs_are_named():
    with pytest.raises(ValueError, match=r"CubicSpring\.w: expected shape \(n,\) or \(n, k\) with k <= 3, "
                                         r"got \(2, 4\)"):
        CubicSpring(np.ones((2, 4)), K3)
    with pytest.raises(ValueError, match=r"UnilateralSpring\.gap: expected a finite value >= 0, got -0\.1"):
        UnilateralSpring([1.0], KU, gap=-0.1)
    with pytest.raises(ValueError, match=r"Jenkins\.kt: expected a scalar, got shape \(2,\)"):
        Jenkins([1.0], [1.0, 2.0], FS)
    with pytest.raises(ValueError, match=r"Elements\[1\] \(Jenkins\)\.w: expected 2 rows"):
        Elements([CubicSpring([1.0, 0.0], K3), Jenkins([1.0], KT, FS)], 2)
    elements = Elements([CubicSpring([1.0], K3)], 1)
    st = Structure.real(np.eye(1), np.eye(1), np.zeros((6, 1)), np.ones(1), np.ones(1), H=1)
    with pytest.raises(ValueError, match="1 elements, the structure's B has 2 blocks"):
        epmc(st, elements, np.array([0.1]), H=1)


def test_one_dimensional_elements_refuse_more_coordinates_and_zero_stiffness():
    with pytest.raises(ValueError, match=r"Jenkins\.w: expected 1 local coordinate\(s\), got 2"):
        Jenkins(np.ones((3, 2)), KT, FS)
    with pytest.raises(ValueError, match=r"TanhFriction\.eps: expected a finite value > 0, got 0"):
        TanhFriction([1.0], FS, eps=0.0)
