"""Hill's method against oracles (docs/method_limits.md §4).

* Duffing oscillator ``ẍ + 2ζẋ + x + κx³ = F cos ωt`` (hardening): the branch between the two folds
  of the forced response is unstable, the rest stable. At H = 1 the oracle is analytic: with
  ``G(s) = s[(1 − ω² + ¾κs)² + (2ζω)²]`` the amplitude relation ``G(a²) = F²``, a solution is a
  saddle (unstable) exactly where ``dG/ds < 0`` (Nayfeh & Mook 1979, §4.1). At H = 3, 5 the oracle is
  the branch's own geometry: unstable where it runs back in ω (folds between neighbours left out).
* Condensing the modes far from every harmonic (large models) keeps the leading exponents.
* Linear (always stuck) friction oscillator with modal damping: every point stable, with the
  Floquet exponents' real parts exactly ``−c_r/2``.
* Tanh friction (forces that depend on velocity; the velocity Jacobian in ``Δ₁``): at small amplitude
  the exponents are the eigenvalues of the system with the damper ``F_s/ε``; where the force
  saturates they are the Floquet exponents of the monodromy matrix of the variational equations
  along the same motion (to Hill's truncation at H = 21), also on a free body whose gauged mean
  position is removed; condensing a stiff mode keeps the leading exponents only with the velocity
  force taken through the condensed modes.
* The matrix ``I + K_c G`` that condenses the modes, formed by harmonic blocks pair by pair, equals the
  sparse product with the dense block-diagonal ``G``.
"""
from dataclasses import replace

import numpy as np
import pytest
import scipy.linalg as sla
from scipy.integrate import solve_ivp

from ringdamper.nonlinear.contact.elements import Elements, TanhFriction
from ringdamper.nonlinear.harmonic_balance.condensed import CondensedHBM, structural_damping
from ringdamper.nonlinear.harmonic_balance.frf import forced_response
from ringdamper.nonlinear.harmonic_balance.stability import (
    BAND,
    _contact_matrix,
    _modal_blocks,
    _through_matrix,
    hill_exponents,
    modal_hill_matrices,
)
from ringdamper.nonlinear.harmonic_balance.structure import Structure
from ringdamper.studies.method_limits.stability import KAPPA, ZETA, duffing_frf

from .systems import cyclic_structure, multi_dof, one_dof


def _exponents(frf, j, band=BAND):
    """Hill's exponents (fundamental strip) at point ``j`` of the forced response ``frf``."""
    model, p = frf.problem.model, frf.points[j]
    ev = replace(model.evaluate(p.z[:-1], p.z[-1], 0.0, frf.problem.gauge, True), gauge=p.payload.gauge)
    return hill_exponents(*modal_hill_matrices(model, ev, p.z[-1], band=band), p.z[-1])


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
    for j in range(0, len(frf.points), 5):
        full, part = _exponents(frf, j, band=np.inf), _exponents(frf, j, band=0.0)
        lead = full[np.argsort(-full.real)[:2]]
        assert np.all(np.min(np.abs(part[:, None] - lead), axis=0) <= 1e-3 * np.abs(lead))


# ---- forces that depend on velocity: TanhFriction -------------------------------------------------

#: two masses, m1 forced; ω_1 = 10, ω_2 = 20 rad/s
CHAIN_M, CHAIN_K = np.diag([1.0, 0.5]), np.array([[300.0, -100.0], [-100.0, 100.0]])
SLIP, EPS = 2.0, 0.5                                     # a damper SLIP/EPS = 4 N s/m at rest


def _tanh_system(M, K, w, H, slip_force=SLIP, eps=EPS, zeta=0.02):
    """``M``, ``K`` with tanh friction on the coordinate ``wᵀq``, modal damping ``zeta``, forced and
    observed at DoF 0."""
    elements = Elements([TanhFriction(w, slip_force, eps)], len(M))
    e = np.eye(len(M))[0]
    return Structure.real(M, K, elements.B, e, e, H=H, zeta=zeta), elements


def _floquet_exponents(structure, element, Q, omega):
    """Floquet exponents ``log(μ)/T`` (principal logarithm: the fundamental strip) of the monodromy
    matrix of ``M δq̈ + (C + w k_v(t) wᵀ) δq̇ + K δq = 0`` along the periodic motion with harmonics
    ``Q`` (``q = Re Σ Q_h e^{ihωt}``), ``k_v = (F_s/ε)(1 − tanh²(wᵀq̇/ε))`` the slope of the tanh
    friction ``element``: the variational equations integrated over one period (DOP853, rtol 1e-12)."""
    hd = structure.harmonics[0]
    M, K, C = hd.M, hd.K, structure.damping_matrix(0).real
    n, w = len(M), element.w[:, 0]
    Minv = np.linalg.inv(M)
    rate = 1j * omega * np.arange(len(Q))[:, None] * np.array(Q)      # harmonics of q̇

    def variational(t, x):
        v = np.real(np.exp(1j * omega * np.arange(len(Q)) * t) @ rate) @ w
        kv = element.slip_force / element.eps * (1 - np.tanh(v / element.eps) ** 2)
        A = np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ K, -Minv @ (C + kv * np.outer(w, w))]])
        return (A @ x.reshape(2 * n, 2 * n)).ravel()

    T = 2 * np.pi / omega
    sol = solve_ivp(variational, (0.0, T), np.eye(2 * n).ravel(), method="DOP853", rtol=1e-12, atol=1e-14)
    return np.log(np.linalg.eigvals(sol.y[:, -1].reshape(2 * n, 2 * n)).astype(complex)) / T


def _mismatch(a, b):
    """Largest distance from a point of either set to the nearest of the other."""
    d = np.abs(a[:, None] - b[None])
    return max(d.min(axis=0).max(), d.min(axis=1).max())


def test_tanh_friction_at_small_amplitude_is_a_linear_viscous_damper():
    """|u̇| ≈ 2e-7 ε: the exponents are the eigenvalues of λ²M + λ(C_s + c wwᵀ) + K, c = F_s/ε,
    shifted into the strip (measured 5e-15 of their size)."""
    w = np.array([0.0, 1.0])
    st, elements = _tanh_system(CHAIN_M, CHAIN_K, w, H=3)
    frf = forced_response(st, elements, 1e-6, 8.0, 12.0, H=3, tol=1e-12)
    assert frf.status == 0 and frf.stable.all()
    C = st.damping_matrix(0).real + SLIP / EPS * np.outer(w, w)
    A = np.block([[np.zeros((2, 2)), np.eye(2)], [-np.linalg.solve(CHAIN_M, CHAIN_K), -np.linalg.solve(CHAIN_M, C)]])
    mu = np.linalg.eigvals(A)
    for j, omega in enumerate(frf.omega):
        lam = _exponents(frf, j)
        assert lam.size == 4
        assert _mismatch(lam, mu - 1j * omega * np.round(mu.imag / omega)) <= 1e-10 * np.max(np.abs(mu))


def test_tanh_friction_exponents_are_the_monodromy_matrix_floquet_exponents():
    """|u̇| ≈ 4.5 ε at ω = 0.9 ω_1 (the friction force saturates): Hill's exponents at H = 21 against
    the monodromy matrix along the same harmonic-balance motion. The difference is Hill's truncation
    of the perturbation and of the spikes of k_v(t) to H harmonics: measured 3.4e-4, 1.0e-5, 2.8e-7
    1/s at H = 9, 15, 21 (exponents of size 1.1 and 2.1 1/s); the integration's own error is ≤ 1e-12
    (measured where the truncation is negligible: |u̇| = 0.2 ε, H ≥ 9). Tolerance 2e-6 1/s at H = 21."""
    st, elements = _tanh_system(CHAIN_M, CHAIN_K, np.array([0.0, 1.0]), H=21)
    frf = forced_response(st, elements, 10.0, 9.0, 9.05, H=21, tol=1e-12, stability=False)
    assert frf.status == 0 and frf.omega[0] == 9.0
    lam = _exponents(frf, 0)
    floquet = _floquet_exponents(st, elements.elements[0], frf.harmonics(0), 9.0)
    assert lam.size == 4 and _mismatch(lam, floquet) <= 2e-6


def test_tanh_friction_on_a_free_body_gauged_directions_removed():
    """m2 free, held by tanh friction on m1 (t = x2 − x1): the gauge pins its mean position, and
    Hill's exponents are those of the monodromy matrix except the neutral one (0: the mean position)
    and the decay of m2’s mean velocity (module docstring). H = 21: measured 3.6e-7 1/s, tolerance 2e-6 1/s
    as above."""
    M, K = np.diag([1.0, 0.3]), np.diag([100.0, 0.0])
    st, elements = _tanh_system(M, K, np.array([-1.0, 1.0]), H=21)
    frf = forced_response(st, elements, 10.0, 8.0, 8.05, H=21, tol=1e-12, stability=False)
    assert frf.status == 0 and frf.points[0].payload.gauge.shape[1] == 1
    lam = _exponents(frf, 0)
    floquet = _floquet_exponents(st, elements.elements[0], frf.harmonics(0), 8.0)
    near = np.argmin(np.abs(floquet[:, None] - lam[None]), axis=0)
    assert lam.size == 2 and np.unique(near).size == 2 and np.max(np.abs(floquet[near] - lam)) <= 2e-6
    neutral, mean_velocity = sorted(np.delete(floquet, near), key=abs)
    assert abs(neutral) <= 1e-9 and mean_velocity.real < -0.1 and mean_velocity.imag == 0


def test_tanh_friction_condensed_modes_keep_the_exponents():
    """A stiff second mode (ω_2 = 182 rad/s) condensed at H = 3 around the first (band 0): the two
    leading exponents within 5e-4 of those with every mode explicit (measured 2.1e-4). The
    velocity force taken through the condensed modes, (I + K_c G)⁻¹ K_v (I + G K_c)⁻¹, matters:
    K_v alone is off by 1.5e-3."""
    M, K = np.diag([1.0, 0.1]), np.array([[3100.0, -3000.0], [-3000.0, 3000.0]])
    st, elements = _tanh_system(M, K, np.array([0.0, 1.0]), H=3, slip_force=5.0, zeta=0.01)
    frf = forced_response(st, elements, 10.0, 8.0, 12.0, H=3, stability=False)
    assert frf.status == 0
    for j in range(0, len(frf.points), 4):
        full, part = _exponents(frf, j, band=np.inf), _exponents(frf, j, band=0.0)
        lead = full[np.argsort(-full.real)[:2]]
        assert np.all(np.min(np.abs(part[:, None] - lead), axis=0) <= 5e-4 * np.abs(lead))


def test_through_matrix_by_harmonic_blocks_equals_the_dense_product():
    """``I + K_c G`` of the condensed modes, formed pair by pair on each harmonic's diagonal block of
    ``G`` (:func:`ringdamper.nonlinear.harmonic_balance.stability._through_matrix`), equals the sparse ``K_c`` times the
    dense block-diagonal ``G`` to 1e-14 of its largest entry on the cyclic toy (complex harmonics),
    at a state whose contact Jacobian couples the harmonics (pairs slipping over part of the period)."""
    st, c, _ = cyclic_structure(H=3)
    model = CondensedHBM(st, c, 3, 36, damping=structural_damping(st, 3, 0.02), forced=True, gamma=1.0)
    y = 3e-4 * np.random.default_rng(7).standard_normal(model.n_core)
    ev = model.evaluate(y, 12.0, 0.0, model.initial_gauge())
    kc = ev.aft.jac
    off_diagonal = kc.copy()
    for k in range(model.C):
        off_diagonal[:, :, k, :, k] = 0.0
    assert np.any(off_diagonal)                          # the harmonics are coupled
    G = _modal_blocks(model, 12.0, 0.0)[3]
    assert sum(np.any(g) for g in G) == model.H + 1      # a condensed receptance on every harmonic
    dense = np.eye(model.n_d) + _contact_matrix(kc, model.p) @ sla.block_diag(*G)
    assert np.max(np.abs(_through_matrix(model, kc, G) - dense)) <= 1e-14 * np.max(np.abs(dense))
