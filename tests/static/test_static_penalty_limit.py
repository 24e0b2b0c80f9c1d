"""The penalty solution converges to the exact (Lagrange) one as kn → ∞, error ~ 1/kn.

Two blocks with a curved initial gap (partial contact). Once kn is large enough for the active
set to be the exact one, N_pen − N_exact is linear in the contact compliance 1/kn: the observed
order of the relative error between successive decades must be 1 (within 0.1).
"""
import numpy as np

from ringdamper.static.solver import solve_static_contact
from ringdamper.static.synthetic import two_blocks

KT = 1.0e3
KNS = 10.0 ** np.arange(3, 8)  # the blocks' own contact stiffness is O(E·h) = O(100)


def test_penalty_converges_to_lagrange_at_rate_one():
    system = two_blocks(gap=lambda x, y: 0.1 * ((x - 0.5) ** 2 + (y - 0.5) ** 2))
    exact = solve_static_contact(system.K, system.f, system.G, system.g0, None, KT,
                                 method="lagrange")
    assert exact.status == 0, exact.reason
    errors, gap_errors = [], []
    for kn in KNS:
        r = solve_static_contact(system.K, system.f, system.G, system.g0, kn, KT)
        assert r.status == 0, r.reason
        errors.append(np.linalg.norm(r.N0 - exact.N0) / np.linalg.norm(exact.N0))
        gap_errors.append(np.abs(r.gap - exact.gap).max() / exact.gap.max())
        final = r
    rates = -np.diff(np.log10(errors))
    print("kn:", KNS, "\nrelative N error:", np.array(errors), "\nobserved orders:", rates,
          "\ngap error:", np.array(gap_errors))
    assert np.all(np.diff(errors) < 0) and np.all(np.diff(gap_errors) < 0)
    np.testing.assert_array_equal(final.in_contact, exact.in_contact)
    assert np.all(np.abs(rates[1:] - 1.0) < 0.1), rates
    assert errors[-1] < 1e-4
