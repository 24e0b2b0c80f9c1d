"""Analytic 1-D oracles (spring chains against a rigid wall / a floating body), both laws.

Chain with springs k_j, node 0 clamped, loads f_i: the tip moves u_free = Σ_i f_i c_i freely
(c_i = Σ_{j≤i} 1/k_j, tip flexibility c). Against a wall at gap g0 the tip force is
N = max(u_free − g0, 0) / (c + 1/kn) (penalty) or max(u_free − g0, 0) / c (exact). A negative g0 = −δ
is an interference of δ (the tip starts δ inside the wall): the same closed forms hold with
u_free − g0 = u_free + δ, i.e. N = kn·(δ + d_n), the penalty spring loaded by the interference plus
the closure d_n = u_free − c·N.
"""
import numpy as np
import pytest

from ringdamper.static.solver import solve_static_contact
from ringdamper.static.synthetic import chain_flexibilities, floating_pair, wall_chain

K_SPRINGS = np.array([3.0e6, 1.5e6, 4.0e6, 2.5e6])
LOADS = np.array([10.0, -4.0, 25.0, 40.0])
KN = 7.0e6
RTOL = 1e-10


def _oracle(g0, method):
    c, c_tip = chain_flexibilities(K_SPRINGS)
    u_free = LOADS @ c
    compliance = c_tip + (1.0 / KN if method == "penalty" else 0.0)
    N = max(u_free - g0, 0.0) / compliance
    d_n = u_free - c_tip * N
    return N, max(g0 - d_n, 0.0), max(d_n - g0, 0.0), u_free


@pytest.mark.parametrize("method", ["penalty", "lagrange"])
@pytest.mark.parametrize("gap_ratio", [-0.5, 0.0, 0.4, 0.999, 1.7])
def test_chain_against_wall(method, gap_ratio):
    u_free = _oracle(0.0, method)[3]
    g0 = gap_ratio * u_free
    system = wall_chain(K_SPRINGS, LOADS, g0)
    r = solve_static_contact(system.K, system.f, system.G, system.g0, KN, 0.0, method=method)
    N, gap, pen, _ = _oracle(g0, method)
    assert r.status == 0, r.reason
    assert r.N0[0] == pytest.approx(N, rel=RTOL, abs=RTOL * LOADS.sum())
    assert r.gap[0] == pytest.approx(gap, rel=RTOL, abs=RTOL * u_free)
    assert r.penetration[0] == pytest.approx(pen, rel=RTOL, abs=RTOL * u_free)
    assert r.in_contact[0] == (N > 0)
    assert r.residual <= 1e-12


@pytest.mark.parametrize("method", ["penalty", "lagrange"])
def test_interference_alone_preloads_the_contact(method):
    """No load, the tip δ = 2 µm inside the wall: N = δ / (c + 1/kn) (penalty: the contact spring and
    the chain in series share the interference; exact law: N = δ / c, the chain pushed back by δ).
    The chain is pushed back uniformly along its flexibilities, u_i = −c_i N."""
    delta = 2.0e-6
    c, c_tip = chain_flexibilities(K_SPRINGS)
    system = wall_chain(K_SPRINGS, np.zeros(K_SPRINGS.size), -delta)
    r = solve_static_contact(system.K, system.f, system.G, system.g0, KN, 0.0, method=method)
    assert r.status == 0, r.reason
    N = delta / (c_tip + (1.0 / KN if method == "penalty" else 0.0))
    assert r.N0[0] == pytest.approx(N, rel=RTOL)
    assert r.in_contact[0] and r.gap[0] == 0.0
    d_n = r.relative_displacement[0, 0]
    assert d_n == pytest.approx(-c_tip * N, rel=RTOL)
    if method == "penalty":      # N0 = kn (interference + closure), the penetration N0 / kn
        assert r.N0[0] == pytest.approx(KN * (delta + d_n), rel=RTOL)
        assert r.penetration[0] == pytest.approx(N / KN, rel=RTOL)
    np.testing.assert_allclose(r.u, -c * N, rtol=RTOL)


@pytest.mark.parametrize("method", ["penalty", "lagrange"])
@pytest.mark.parametrize("g0", [0.0, 3e-6])
def test_floating_body_held_only_by_contact(method, g0):
    """K is singular (B is free); the contact carries exactly the push; B crosses the gap."""
    k_a, k_b, push = np.array([2.0e6, 5.0e6]), 3.0e6, 12.0
    system = floating_pair(k_a, k_b, push, g0)
    r = solve_static_contact(system.K, system.f, system.G, system.g0, KN, 0.0, method=method)
    assert r.status == 0, r.reason
    assert r.N0[0] == pytest.approx(push, rel=RTOL)
    pen = push / KN if method == "penalty" else 0.0
    assert r.penetration[0] == pytest.approx(pen, rel=RTOL, abs=RTOL * g0 + 1e-20)
    assert r.in_contact[0] and r.gap[0] == 0.0        # exact complementarity by contract
    u_tip = -push * chain_flexibilities(k_a)[1]
    u_near = u_tip - g0 - pen
    expected = np.array([-push / k_a[0], u_tip, u_near, u_near - push / k_b])
    np.testing.assert_allclose(r.u, expected, rtol=RTOL)
