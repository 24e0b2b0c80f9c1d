"""Two elastic blocks (Q1 hexahedra) pressed together through matching node pairs.

Block A is clamped at its base; block B is held only by the contact (normal law + tangential
sticking springs) unless stated. Tolerances: force resultants and balance 1e-8 relative.
"""
import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ringdamper.static.solver import solve_static_contact
from ringdamper.static.synthetic import assert_kkt, contact_forces, two_blocks

KN, KT = 1.0e4, 1.0e3
METHODS = ["penalty", "lagrange"]


def _tilted(x):
    """Body force on B pressing with resultant −1 and a moment that lifts the x = 1 side."""
    return np.stack([0 * x[0], 0 * x[0], -1.0 + 3.0 * (x[0] - 0.5)])


def _solve(system, method, **kwargs):
    return solve_static_contact(system.K, system.f, system.G, system.g0, KN, KT, method=method,
                                **kwargs)


@pytest.mark.parametrize("method", METHODS)
def test_pressed_blocks_carry_the_load(method):
    """ΣN equals the applied resultant; KKT and B's global force balance."""
    system = two_blocks()
    r = _solve(system, method)
    assert_kkt(r, system, KT)
    resultant = -system.f[system.ring][system.component[system.ring] == 2].sum()
    assert resultant == pytest.approx(1.0, rel=1e-12)
    assert r.N0.sum() == pytest.approx(resultant, rel=1e-8)
    assert np.all(r.in_contact)
    assert np.abs(r.tangential.sum(axis=0)).max() <= 1e-8 * resultant


@pytest.mark.parametrize("method", METHODS)
def test_zero_load_invents_nothing(method):
    """Test 4a: f = 0 gives u = 0, N = 0 and the gaps at rest."""
    system = two_blocks(gap=lambda x, y: 1e-3 * x)
    r = solve_static_contact(system.K, 0 * system.f, system.G, system.g0, KN, KT, method=method)
    assert r.status == 0, r.reason
    assert np.all(r.N0 == 0) and not r.in_contact.any()
    assert np.abs(r.u).max() <= 1e-12 * system.g0.max()
    np.testing.assert_allclose(r.gap, system.g0, rtol=1e-12)
    assert r.residual <= 1e-12


@pytest.mark.parametrize("method", METHODS)
def test_normal_forces_scale_with_the_load(method):
    """Test 4b: with g0 = 0 the problem is positively homogeneous: N(α f) = α N(f)."""
    system = two_blocks(load=_tilted)
    r1 = _solve(system, method)
    r2 = solve_static_contact(system.K, 3.7 * system.f, system.G, system.g0, KN, KT, method=method)
    assert r1.status == 0 and r2.status == 0
    np.testing.assert_array_equal(r1.in_contact, r2.in_contact)
    np.testing.assert_allclose(r2.N0, 3.7 * r1.N0, rtol=1e-10, atol=1e-10 * r2.N0.max())
    np.testing.assert_allclose(r2.gap, 3.7 * r1.gap, rtol=1e-10, atol=1e-10 * r2.gap.max())


@pytest.mark.parametrize("method", METHODS)
def test_pulling_apart_opens_every_pair(method):
    """Test 4c: both blocks supported, B pulled up: N = 0 and gap = g0 − d_n of the free solve."""
    system = two_blocks(load=lambda x: np.stack([0 * x[0], 0 * x[0], 1.0 + 0 * x[0]]),
                        gap=lambda x, y: 1e-4 * (1 + x + y), clamp_ring_top=True)
    r = _solve(system, method)
    assert r.status == 0, r.reason
    assert np.all(r.N0 == 0) and not r.in_contact.any()
    Gt = sp.vstack([system.G[1::3], system.G[2::3]])
    u_free = spla.spsolve((system.K + KT * Gt.T @ Gt).tocsc(), system.f)
    expected_gap = system.g0 - system.G[0::3] @ u_free
    assert np.all(expected_gap > system.g0)
    np.testing.assert_allclose(r.gap, expected_gap, rtol=1e-10)
    np.testing.assert_allclose(r.u, u_free, rtol=1e-10, atol=1e-12 * np.abs(u_free).max())


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("case", ["tilted load", "curved gap"])
def test_partial_contact(method, case):
    """Some pairs separate; the active set is found and KKT holds."""
    if case == "tilted load":
        system = two_blocks(load=_tilted)
    else:
        system = two_blocks(gap=lambda x, y: 0.1 * ((x - 0.5) ** 2 + (y - 0.5) ** 2))
    r = _solve(system, method)
    assert_kkt(r, system, KT)
    closed = r.in_contact
    assert 0 < closed.sum() < closed.size
    assert r.gap[closed].max() <= 1e-12 * r.gap.max() and np.all(r.N0[~closed] == 0)
    assert np.all(r.gap[~closed] > 0)
    x, y = system.points.T
    if case == "tilted load":
        assert np.all(x[~closed] > 0.5) and np.all(closed[x == 0])
    else:  # the open pairs are the outer ones: symmetric about the centre, which is closed
        radius = np.hypot(x - 0.5, y - 0.5)
        assert radius[closed].max() < radius[~closed].min()
    assert r.N0.sum() == pytest.approx(1.0, rel=1e-8)


@pytest.mark.parametrize("case", ["tilted load", "curved gap"])
def test_lagrange_state_is_exactly_complementary(case):
    """The active set decides: gap is 0 to the bit on active pairs although g0 − d_n there is
    only round-off (its value depends on the BLAS/SIMD path), and N0 is 0 on open pairs."""
    if case == "tilted load":
        system = two_blocks(load=_tilted)
    else:
        system = two_blocks(gap=lambda x, y: 0.1 * ((x - 0.5) ** 2 + (y - 0.5) ** 2))
    r = _solve(system, "lagrange")
    raw_gap = system.g0 - r.relative_displacement[:, 0]
    assert np.abs(raw_gap[r.in_contact]).max() > 0          # the projection has work to do here
    assert np.all(r.gap[r.in_contact] == 0.0) and np.all(r.N0[~r.in_contact] == 0.0)
    assert np.max(r.N0 * r.gap) == 0.0
    assert r.complementarity <= 1e-12                        # what the projection removed


def test_both_laws_agree_on_the_active_set():
    """A stiff penalty finds the exact active set; N agrees to O(structure stiffness / kn)."""
    system = two_blocks(load=_tilted)
    exact = _solve(system, "lagrange")
    stiff = solve_static_contact(system.K, system.f, system.G, system.g0, 1e8, KT)
    np.testing.assert_array_equal(stiff.in_contact, exact.in_contact)
    assert np.abs(stiff.N0 - exact.N0).max() <= 1e-4 * exact.N0.max()


def test_lagrange_solution_does_not_depend_on_the_scale():
    system = two_blocks(gap=lambda x, y: 0.1 * ((x - 0.5) ** 2 + (y - 0.5) ** 2))
    results = [solve_static_contact(system.K, system.f, system.G, system.g0, s, KT,
                                    method="lagrange") for s in (None, 1e2, 1e6)]
    for r in results[1:]:
        assert r.status == 0
        np.testing.assert_allclose(r.N0, results[0].N0, rtol=1e-8, atol=1e-10)
        np.testing.assert_allclose(contact_forces(r), contact_forces(results[0]), atol=1e-9)
