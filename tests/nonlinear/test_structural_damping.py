"""Structural damping of a user's structure (``C`` or modal ratios) in every analysis.

Oracles:

* Linear 2-DoF system with Rayleigh damping ``C = a M + b K`` (contact open over the whole period):
  the EPMC returns the first mode at every amplitude, ``ω = ω₁`` and ``ζ = (a/ω₁ + b ω₁)/2``
  (Krack's definition: the negative damping acts on ``M``), with and without the stuck shortcut.
* Friction 2-DoF system with mass-proportional damping ``C = a M``: the equation of motion is the
  undamped one with ``ξ − a`` in place of ``ξ``, so the damped backbone is the undamped one with ξ
  shifted by ``a`` at every amplitude, slipping points included (1e-9 relative on ω, 1e-8 on ξ).
  Its E-EBM forcing equals the undamped backbone's with the same damping given as ``zeta_s``
  (``c_r = a`` for every mode), i.e. the damping is counted once.
* Forced response of the linear system: every point on the receptance ``(K − ω²M + iωC)⁻¹ F``
  (1e-8 relative, Newton tolerance 1e-12).
* Damping not diagonal in the modes (a dashpot on one DoF): every mode becomes explicit; the EPMC of
  the linear system solves ``det(K − ω²M + iω(C − ξM)) = 0`` (solved here directly; 1e-9 on ω and
  Newton's 1e-8·ω on ξ, measured 3e-10 and 1e-8·ξ with ζ = 0.56 %); the forced response is the
  receptance and its Hill exponents the eigenvalues of ``λ²M + λC + K`` (largest real part to 1e-9).
* Time domain: shooting (``ringdamper.nonlinear.time_domain.shooting``) with modal ratios, and with a dashpot,
  agrees with the damped EPMC at H = 15 on the friction 2-DoF system (ω within 1e-6, ζ within 1e-6;
  measured 2e-8 and 1e-7 with modal ratios, 2e-8 and 9e-8 with the dashpot).
"""
import numpy as np
import pytest
from scipy.optimize import fsolve

from ringdamper.nonlinear.contact.friction import FrictionContacts
from ringdamper.nonlinear.harmonic_balance.condensed import CondensedHBM, structural_damping
from ringdamper.nonlinear.harmonic_balance.eebm import eebm
from ringdamper.nonlinear.harmonic_balance.epmc import epmc, linear_limit
from ringdamper.nonlinear.harmonic_balance.frf import forced_response
from ringdamper.nonlinear.harmonic_balance.structure import Structure
from ringdamper.nonlinear.time_domain.shooting import hbm_state, phase_row, shoot
from ringdamper.status import Status

M = np.diag([1.0, 0.5])
K = np.array([[4.0e4, -1.0e4], [-1.0e4, 1.0e4]])
B = np.array([[0.0, 0.0], [0.0, 1.0], [0.0, 0.0]])       # one pair on DoF 2 (tangential t1)
E = np.eye(2)[0]
FRICTION = FrictionContacts(kn=1e6, kt=1e3, mu=0.25, N0=20.0, gap=0.0)
OPEN = FrictionContacts(kn=1e6, kt=1e3, mu=0.25, N0=0.0, gap=1.0)   # never closes
DASHPOT = np.diag([6.0, 0.0])           # on DoF 1 only: not diagonal in the modes of (K, M)


def _natural_frequencies():
    return np.sqrt(np.sort(np.linalg.eigvals(np.linalg.solve(M, K)).real))


def _structure(H=3, **damping):
    return Structure.real(M, K, B, E, E, H=H, **damping)


@pytest.mark.parametrize("shortcut", [True, False], ids=["stuck_shortcut", "continuation"])
def test_rayleigh_damping_gives_the_modal_frequency_and_ratio_at_every_amplitude(shortcut):
    a, b = 3.0, 2e-4
    w1 = _natural_frequencies()[0]
    tol = 1e-12                          # Newton's on ξ/ω: ζ = ξ/(2ω) is then right to tol/2
    bb = epmc(_structure(C=a * M + b * K), OPEN, np.geomspace(1e-3, 1e-1, 5), H=3, tol=tol,
              stuck_shortcut=shortcut)
    assert np.all(bb.status == Status.CONVERGED)
    np.testing.assert_allclose(bb.omega, w1, rtol=1e-12)
    np.testing.assert_allclose(bb.zeta, (a / w1 + b * w1) / 2, rtol=0, atol=tol / 2)


def test_modal_ratios_give_their_ratio():
    bb = epmc(_structure(zeta=np.array([0.02, 0.05])), OPEN, np.geomspace(1e-3, 1e-1, 3), H=1)
    np.testing.assert_allclose(bb.zeta, 0.02, rtol=1e-10)
    np.testing.assert_allclose(bb.omega, _natural_frequencies()[0], rtol=1e-12)


def test_mass_proportional_damping_shifts_xi_of_the_friction_backbone_and_counts_once_in_the_eebm():
    a = 3.0
    alpha = np.geomspace(1e-3, 1.0, 12)
    undamped = epmc(_structure(), FRICTION, alpha, H=3)
    damped = epmc(_structure(C=a * M), FRICTION, alpha, H=3)
    assert np.all(undamped.status == Status.CONVERGED) and np.all(damped.status == Status.CONVERGED)
    assert np.max(undamped.zeta) > 0.01                  # the friction damps: slipping points
    np.testing.assert_allclose(damped.omega, undamped.omega, rtol=1e-9)
    np.testing.assert_allclose(damped.xi - a, undamped.xi, rtol=0, atol=1e-8 * a)
    same_damping_as_zeta_s = a / (2 * _natural_frequencies())   # c_r = 2 zeta_r w_r = a
    np.testing.assert_allclose(eebm(damped).gamma, eebm(undamped, zeta_s=same_damping_as_zeta_s).gamma,
                               rtol=1e-9)


def test_forced_response_of_the_damped_linear_system_is_its_receptance():
    C = 3.0 * M + 2e-4 * K
    w1 = _natural_frequencies()[0]
    frf = forced_response(_structure(C=C), OPEN, 1.0, 0.9 * w1, 1.1 * w1, H=1, tol=1e-12, stability=False)
    assert frf.status == Status.CONVERGED and frf.omega.size > 5
    exact = [abs(np.linalg.solve(K - w * w * M + 1j * w * C, E)[0]) for w in frf.omega]
    np.testing.assert_allclose(frf.q_h1, exact, rtol=1e-8)


@pytest.mark.parametrize("damping", [{"zeta": np.array([0.01, 0.03])}, {"C": 0.1 * DASHPOT}],
                         ids=["modal_ratios", "dashpot"])
def test_shooting_with_structural_damping_agrees_with_the_damped_epmc(damping):
    st = _structure(H=15, **damping)
    _, phi = st.stuck_modes(FRICTION.stuck_stiffness().ravel())
    alpha = np.array([3.0, 10.0]) * linear_limit(st, FRICTION, phi[:, 0])
    bb = epmc(st, FRICTION, alpha, H=15, nt=1024, tol=1e-10)
    assert np.all(bb.status == Status.CONVERGED)
    for i in range(alpha.size):
        x0, omega, xi = hbm_state(bb, FRICTION, i)
        res = shoot(st, FRICTION, alpha[i], x0, omega, xi, phase_row(bb), n_steps=1024)
        assert abs(res.omega / omega - 1) <= 1e-6
        assert abs(res.zeta - bb.zeta[i]) <= 1e-6


def test_damping_given_twice_is_refused_by_name():
    damped = _structure(C=3.0 * M)
    bb = epmc(damped, OPEN, np.array([1e-3]), H=1)
    with pytest.raises(ValueError, match="zeta_s"):
        eebm(bb, zeta_s=1e-3)
    with pytest.raises(ValueError, match="zeta_s"):
        forced_response(damped, OPEN, 1.0, 100.0, 120.0, H=1, zeta_s=1e-3)
    with pytest.raises(ValueError, match="C or as modal ratios zeta, not both"):
        _structure(C=3.0 * M, zeta=0.01)


def _epmc_eigenvalue(C, omega0):
    """The EPMC's linear solution, solved directly: ``(K − ω² M + i ω (C − ξ M)) φ = 0`` has a
    non-trivial ``φ``, i.e. ``det = 0`` (two real equations for ω and ξ), from ``(omega0, 0)``."""
    def det(x):
        w, xi = x
        d = np.linalg.det(K - w * w * M + 1j * w * (C - xi * M))
        return [d.real, d.imag]
    return fsolve(det, [omega0, 0.0], xtol=1e-12)


def test_a_dashpot_on_one_dof_couples_the_modes_and_every_mode_becomes_explicit():
    st = _structure(C=DASHPOT)
    off = st.modal(1).coupling
    assert off is not None and abs(off[0, 1]) > 0.1 * np.max(np.abs(st.modal(1).c))
    model = CondensedHBM(st, OPEN, 2, 16, damping=structural_damping(st, 2))
    assert all(np.array_equal(S, np.arange(2)) for S in model.S)
    assert all(Cs.size == 0 for Cs in model.Cset)
    assert _structure(C=3.0 * M + 2e-4 * K).modal(1).coupling is None


@pytest.mark.parametrize("shortcut", [True, False], ids=["stuck_shortcut", "continuation"])
def test_non_modal_damping_gives_the_epmc_eigenvalue_at_every_amplitude(shortcut):
    w, xi = _epmc_eigenvalue(DASHPOT, _natural_frequencies()[0])
    assert xi > 0.5                                         # the dashpot damps the first mode
    bb = epmc(_structure(C=DASHPOT), OPEN, np.geomspace(1e-3, 1e-1, 5), H=3, stuck_shortcut=shortcut)
    assert np.all(bb.status == Status.CONVERGED)
    np.testing.assert_allclose(bb.omega, w, rtol=1e-9)
    np.testing.assert_allclose(bb.xi, xi, rtol=0, atol=1e-8 * w)     # Newton's tolerance (ξ scaled by ω)


def test_forced_response_with_non_modal_damping_is_its_receptance_and_hill_its_eigenvalues():
    """Every point on ``(K − ω²M + iωC)⁻¹ F``; the Hill exponents of a linear system are its
    eigenvalues ``λ² M + λ C + K`` (in the fundamental strip), so the largest real part is the
    least damped one's at every point."""
    w1 = _natural_frequencies()[0]
    frf = forced_response(_structure(C=DASHPOT), OPEN, 1.0, 0.9 * w1, 1.1 * w1, H=1, tol=1e-12)
    assert frf.status == Status.CONVERGED and frf.omega.size > 5
    exact = [abs(np.linalg.solve(K - w * w * M + 1j * w * DASHPOT, E)[0]) for w in frf.omega]
    np.testing.assert_allclose(frf.q_h1, exact, rtol=1e-8)
    state = np.block([[np.zeros((2, 2)), np.eye(2)], [-np.linalg.solve(M, K), -np.linalg.solve(M, DASHPOT)]])
    np.testing.assert_allclose(frf.growth, np.max(np.linalg.eigvals(state).real), rtol=1e-9)
    assert np.all(frf.stable)


def test_damping_not_proportional_to_the_stuck_system_gives_its_complex_eigenvalue():
    """Modal ratios of ``(K, M)``, but the stuck contact spring makes the stuck system's damping
    non-proportional: at light damping the EPMC's stuck points are the first complex eigenvalue
    ``λ`` of ``(K + Bᵀ k B, C, M)``, ``ω = |λ|``, ``ζ = −Re λ / |λ|`` (measured 1.5e-12 and 5.2e-7;
    with ratios 0.01 / 0.08 the EPMC's definition differs by 0.3 % in ζ, docs/library.md)."""
    contacts = FrictionContacts(kn=1e6, kt=1e4, mu=0.25, N0=20.0, gap=0.0)
    st = _structure(H=1, zeta=0.002)
    bb = epmc(st, contacts, np.array([1e-4, 2e-4]), H=1)
    assert np.all(bb.status == Status.CONVERGED)
    stuck = K + B.T @ np.diag(contacts.stuck_stiffness().ravel()) @ B
    C = st.damping_matrix(1).real
    state = np.block([[np.zeros((2, 2)), np.eye(2)], [-np.linalg.solve(M, stuck), -np.linalg.solve(M, C)]])
    lam = np.linalg.eigvals(state)
    lam = lam[lam.imag > 0]
    first = lam[np.argmin(np.abs(lam))]
    np.testing.assert_allclose(bb.omega, abs(first), rtol=1e-10)
    np.testing.assert_allclose(bb.zeta, -first.real / abs(first), rtol=1e-5)
