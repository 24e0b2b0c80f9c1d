"""Receptance of condensed modes (ringdamper.nonlinear.harmonic_balance.receptance): the far modes'
series, undamped and with modal damping, against the direct sum inside and beyond its reach, the number of terms,
real arithmetic at h = 0, and the Jacobians of the cyclic toy (and Hill's condensed receptance) formed with it
against those
formed by the direct sum."""
import sys

import numpy as np

from ringdamper.nonlinear.harmonic_balance.condensed import CondensedHBM
from ringdamper.nonlinear.harmonic_balance.receptance import (
    FAR,
    REACH,
    TOL,
    DampedReceptance,
    Receptance,
    damped_terms_needed,
    terms_needed,
)

from .systems import cyclic_structure


def _modes(rng, p=12, m=60):
    """Modes like a Craig–Bampton model's: six near s = 1, the others far above it (ω² up to 1e6)."""
    w2 = np.r_[rng.uniform(0.3, 3.0, 6), np.geomspace(200.0, 1e6, m - 6)]
    return w2, rng.standard_normal((p, m)) + 1j * rng.standard_normal((p, m))


def _direct(w2, Psi, s):
    return (Psi / (w2 - s)) @ Psi.conj().T


def test_series_equals_the_direct_sum_inside_and_beyond_its_reach():
    """Expanded about s₀ = 1 + 0.01i: the six modes below FAR²|s₀| = 100 are summed directly, the 54 above
    by the series; within 1e-13 of the direct sum (relative to its largest entry) at s₀, around it, at
    the edge of the stored terms' reach and beyond it (where the direct sum takes over)."""
    rng = np.random.default_rng(1)
    w2, Psi = _modes(rng)
    s0 = 1.0 + 0.01j
    receptance = Receptance(w2, Psi, Psi.conj().T.copy(), s0)
    for s in (s0, 0.9 + 0.05j, 1.5 * s0, 0.99 * REACH * s0, 5 * REACH * s0, 300.0 + 0.01j):   # 300: past 200
        ref = _direct(w2, Psi, s)
        assert np.max(np.abs(receptance(s) - ref)) <= 1e-13 * np.max(np.abs(ref)), s
    assert FAR ** 2 * abs(s0) < 200.0 and receptance.near.size == 6
    assert len(receptance.terms) == terms_needed(REACH * abs(s0) / 200.0) > 1


def test_terms_bring_the_remainder_to_the_tolerance_and_no_further():
    for q in (1e-6, 1e-3, 0.01, 0.3):
        K = terms_needed(q)
        assert q ** K / (1 - q) <= TOL < q ** (K - 1) / (1 - q), q
    assert terms_needed(0.0) == 1
    assert terms_needed(1.0) == terms_needed(2.0) == sys.maxsize          # diverges: the direct sum


def test_real_modes_at_zero_shift_stay_real():
    """Harmonic 0 (z_r = ω_r², s = 0): real modes give a real receptance, Ψ diag(1/ω²) Ψᵀ."""
    rng = np.random.default_rng(2)
    w2, Psi = _modes(rng)
    Psi = Psi.real.copy()
    G = Receptance(w2, Psi, Psi.T.copy(), 0.0)(0.0)
    assert np.isrealobj(G)
    np.testing.assert_allclose(G, (Psi / w2) @ Psi.T, rtol=1e-13, atol=1e-13 * np.max(np.abs(G)))


def test_jacobian_with_the_series_equals_the_direct_one():
    """The cyclic toy's EPMC Jacobian at ω = 12 rad/s, ξ = 0.3 (its 7 condensed modes a harmonic at
    100–314 rad/s: all far at h = 0 and 1, two near at h = 2, all near at h = 3) formed with the series
    and with the direct sum agree to 1e-13 of the largest entry."""
    st, c, _ = cyclic_structure(H=3)
    model = CondensedHBM(st, c, 3, 36, expansion=(12.0, 0.3))
    rng = np.random.default_rng(5)
    y = 1e-4 * rng.standard_normal(model.n_core)
    J = model.evaluate(y, 12.0, 0.3, model.initial_gauge()).J.toarray()
    assert [r.near.size for r in model.receptances] == [0, 0, 2, 7]
    plain = CondensedHBM(st, c, 3, 36)                                  # no expansion point: direct sums
    assert plain.receptances == [None] * 4
    direct = plain.evaluate(y, 12.0, 0.3, plain.initial_gauge()).J.toarray()
    assert np.max(np.abs(J - direct)) <= 1e-13 * np.max(np.abs(direct))


def _damped_direct(w2, c, Psi, u):
    return (Psi / (w2 - u * u + 1j * u * c)) @ Psi.conj().T


def test_damped_series_equals_the_direct_sum_inside_and_beyond_its_reach():
    """Modal damping c_r = 2 ζ_r ω_r with ζ_r from 1e-4 to 0.5 (β_r = 2ζ_r up to the series' limit of 1) and
    two overdamped modes (β = 3: summed directly whatever their frequency). Expanded about u₀ = 1: within
    1e-13 of the direct sum (relative to its largest entry) at u₀, around it, at the edge of the stored
    terms' reach and beyond it (where the direct sum takes over)."""
    rng = np.random.default_rng(3)
    w2, Psi = _modes(rng)
    zeta = np.geomspace(1e-4, 0.5, w2.size)
    zeta[[10, 40]] = 1.5
    c = 2.0 * zeta * np.sqrt(w2)
    receptance = DampedReceptance(w2, c, Psi, Psi.conj().T.copy(), 1.0)
    for u in (1.0, 0.9, 1.3, 0.99 * REACH, 5 * REACH, -1.2, 3 * FAR):     # 3 FAR: past the far modes' poles
        ref = _damped_direct(w2, c, Psi, u)
        assert np.max(np.abs(receptance(u) - ref)) <= 1e-13 * np.max(np.abs(ref)), u
    assert receptance.near.size == 6 + 2
    assert len(receptance.terms) == damped_terms_needed(REACH / receptance.far_min) > 1


def test_damped_terms_bring_the_bound_to_the_tolerance_and_no_further():
    def bound(q, K):                                                    # Σ_{k≥K} (k + 1) q^k
        return q ** K * (K + 1 - K * q) / (1 - q) ** 2

    for q in (1e-6, 1e-3, 0.1, 0.3):
        K = damped_terms_needed(q)
        assert bound(q, K) <= TOL < bound(q, K - 1), q
        assert np.isclose(bound(q, K), sum((k + 1) * q ** k for k in range(K, K + 400)), rtol=1e-9)
    assert damped_terms_needed(0.0) == 1
    assert damped_terms_needed(1.0) == damped_terms_needed(2.0) == sys.maxsize    # diverges: the direct sum


def test_forced_jacobian_and_hill_receptance_with_the_damped_series_equal_the_direct_ones():
    """The cyclic toy with modal damping (ζ_s = 2 %), forced (ξ = 0) at ω = 12 rad/s (its 7 modes a harmonic at
    100–314 rad/s: all far at h = 1, two near at h = 2, all near at h = 3): its Jacobian formed with the
    damped series and with the direct sum agree to 1e-13 of the largest entry, and so does the receptance of
    the modes Hill's method condenses (:func:`ringdamper.nonlinear.harmonic_balance.stability._rest_receptance`:
    the model's, less the modes kept, here those below 165 rad/s) against its direct sum."""
    from ringdamper.nonlinear.harmonic_balance.condensed import structural_damping
    from ringdamper.nonlinear.harmonic_balance.stability import _rest_receptance

    st, c, _ = cyclic_structure(H=3)
    damping = structural_damping(st, 3, 0.02)
    model = CondensedHBM(st, c, 3, 36, damping=damping, forced=True, gamma=1.0, expansion=(12.0, 0.0))
    rng = np.random.default_rng(7)
    y = 1e-4 * rng.standard_normal(model.n_core)
    J = model.evaluate(y, 12.0, 0.0, model.initial_gauge()).J.toarray()
    assert [type(r).__name__ for r in model.receptances] == ["Receptance"] + ["DampedReceptance"] * 3
    assert [r.near.size for r in model.receptances[1:]] == [0, 2, 7]
    for h in (1, 2, 3):
        m = model.modal[h]
        z = model._modal_impedance(h, 12.0, 0.0)[0]
        keep = np.sqrt(m.w2) <= 165.0
        rest = _rest_receptance(model, h, 12.0, z, keep)
        ref = (m.Psi[:, ~keep] / z[~keep]) @ m.Psi[:, ~keep].conj().T
        assert 0 < keep.sum() < keep.size
        assert np.max(np.abs(rest - ref)) <= 1e-13 * np.max(np.abs(ref)), h
    plain = CondensedHBM(st, c, 3, 36, damping=damping, forced=True, gamma=1.0)   # direct sums
    direct = plain.evaluate(y, 12.0, 0.0, plain.initial_gauge()).J.toarray()
    assert np.max(np.abs(J - direct)) <= 1e-13 * np.max(np.abs(direct))
