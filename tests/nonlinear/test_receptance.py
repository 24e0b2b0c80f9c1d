"""Receptance of undamped condensed modes (ringdamper.nonlinear.receptance): the far modes' series
against the direct sum inside and beyond its reach, the number of terms, real arithmetic at h = 0, and
the Jacobian of the cyclic toy formed with it against the one formed by the direct sum."""
import numpy as np

from ringdamper.nonlinear.condensed import CondensedHBM
from ringdamper.nonlinear.receptance import FAR, REACH, TOL, Receptance, terms_needed

from .systems import cyclic_structure


def _modes(rng, p=12, m=60):
    """Modes like a Craig–Bampton model's: six near s = 1, the others far above it (ω² up to 1e6)."""
    w2 = np.r_[rng.uniform(0.3, 3.0, 6), np.geomspace(200.0, 1e6, m - 6)]
    return w2, rng.standard_normal((p, m)) + 1j * rng.standard_normal((p, m))


def _direct(w2, Psi, s):
    return (Psi / (w2 - s)) @ Psi.conj().T


def test_series_equals_the_direct_sum_inside_and_beyond_its_reach():
    """First call at s₀ = 1 + 0.01i: the six modes below FAR²|s₀| = 100 are summed directly, the 54 above
    by the series; within 1e-13 of the direct sum (relative to its largest entry) at s₀, around it, at
    the edge of the stored terms' reach and beyond it (where the direct sum takes over)."""
    rng = np.random.default_rng(1)
    w2, Psi = _modes(rng)
    receptance = Receptance(w2, Psi, Psi.conj().T.copy())
    s0 = 1.0 + 0.01j
    for s in (s0, 0.9 + 0.05j, 1.5 * s0, 0.99 * REACH * s0, 5 * REACH * s0):
        ref = _direct(w2, Psi, s)
        assert np.max(np.abs(receptance(s) - ref)) <= 1e-13 * np.max(np.abs(ref)), s
    assert FAR ** 2 * abs(s0) < 200.0 and receptance.near.size == 6
    assert len(receptance.terms) == terms_needed(REACH * abs(s0) / 200.0) > 1


def test_terms_bring_the_remainder_to_the_tolerance_and_no_further():
    for q in (1e-6, 1e-3, 0.01, 0.3):
        K = terms_needed(q)
        assert q ** K / (1 - q) <= TOL < q ** (K - 1) / (1 - q), q
    assert terms_needed(0.0) == 1


def test_real_modes_at_zero_shift_stay_real():
    """Harmonic 0 (z_r = ω_r², s = 0): real modes give a real receptance, Ψ diag(1/ω²) Ψᵀ."""
    rng = np.random.default_rng(2)
    w2, Psi = _modes(rng)
    Psi = Psi.real.copy()
    G = Receptance(w2, Psi, Psi.T.copy())(0.0)
    assert np.isrealobj(G)
    np.testing.assert_allclose(G, (Psi / w2) @ Psi.T, rtol=1e-13, atol=1e-13 * np.max(np.abs(G)))


def test_jacobian_with_the_series_equals_the_direct_one():
    """The cyclic toy's EPMC Jacobian at ω = 12 rad/s, ξ = 0.3 (its 7 condensed modes a harmonic at
    100–314 rad/s: all far at h = 0 and 1, two near at h = 2, all near at h = 3) formed with the series
    and with the direct sum agree to 1e-13 of the largest entry."""
    st, c, _ = cyclic_structure(H=3)
    model = CondensedHBM(st, c, 3, 36)
    rng = np.random.default_rng(5)
    y = 1e-4 * rng.standard_normal(model.n_core)
    J = model.evaluate(y, 12.0, 0.3).J.toarray()
    assert [r.near.size for r in model.receptances] == [0, 0, 2, 7]
    model.receptances = [None] * len(model.receptances)
    direct = model.evaluate(y, 12.0, 0.3).J.toarray()
    assert np.max(np.abs(J - direct)) <= 1e-13 * np.max(np.abs(direct))
