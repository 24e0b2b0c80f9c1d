"""Absurd physics ends with status ≠ 0 and a reason, never an exception; bad argument
shapes raise ValueError naming the argument. Also the Lagrange fallback path (augmented
Lagrangian) and the round-off guard."""
import numpy as np
import pytest
import scipy.sparse as sp

import ringdamper.static.solver as static
from ringdamper.static.solver import solve_static_contact
from ringdamper.static.synthetic import floating_pair, two_blocks

KN, KT = 1.0e4, 1.0e3
METHODS = ["penalty", "lagrange"]


@pytest.fixture(scope="module")
def blocks():
    return two_blocks()


def _with_nan_in_K(s):
    K = s.K.copy()
    K.data[3] = np.nan
    return dict(K=K)


def _asymmetric(s):
    K = s.K.tolil()
    K[0, 1] += 1.0
    return dict(K=K.tocsr())


ABSURD = {  # name: (changes to the arguments, expected status, word expected in the reason)
    "kn = 0": (lambda s: dict(kn=0.0), 2, "kn"),
    "kn < 0": (lambda s: dict(kn=-KN), 2, "kn"),
    "kn NaN at one pair": (lambda s: dict(kn=np.where(np.arange(s.g0.size) == 3, np.nan, KN)),
                           2, "kn"),
    "kt < 0": (lambda s: dict(kt=-KT), 2, "kt"),
    "NaN in K": (_with_nan_in_K, 2, "K"),
    "inf in f": (lambda s: dict(f=np.where(np.arange(s.f.size) == 0, np.inf, s.f)), 2, "f"),
    "NaN in g0": (lambda s: dict(g0=np.where(np.arange(s.g0.size) == 0, np.nan, s.g0)), 2, "g0"),
    "K not symmetric": (_asymmetric, 2, "symmetric"),
    "free body, no contact at all": (lambda s: dict(G=s.G[:0], g0=s.g0[:0]), 3, "restrained"),
    "free body, no tangential spring": (lambda s: dict(kt=0.0), 3, "restrained"),
    "free body pulled off": (lambda s: dict(f=-s.f), 1, "no equilibrium"),
    "iteration budget": (lambda s: dict(g0=0.1 * (np.arange(s.g0.size) % 3), max_iter=0), 1,
                         "converge"),
}


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("case", list(ABSURD))
def test_absurd_physics_returns_a_status(blocks, method, case):
    change, status, word = ABSURD[case]
    args = dict(K=blocks.K, f=blocks.f, G=blocks.G, g0=blocks.g0, kn=KN, kt=KT, method=method)
    args.update(change(blocks))
    r = solve_static_contact(**args)
    assert r.status == status, r.reason
    assert not r.converged and word in r.reason
    assert r.N0.shape == (args["g0"].size,) and r.u.shape == (blocks.K.shape[0],)


@pytest.mark.parametrize("method", METHODS)
def test_floating_body_pushed_away_has_no_equilibrium(method):
    system = floating_pair([1.0, 2.0], 3.0, -1.0, 0.0)
    r = solve_static_contact(system.K, system.f, system.G, system.g0, 10.0, 0.0, method=method)
    assert r.status == 1 and "no equilibrium" in r.reason


@pytest.mark.parametrize("change, name", [
    (dict(f=np.zeros(3)), "f"),
    (dict(G=sp.csr_matrix((6, 4))), "G"),
    (dict(g0=np.zeros((1, 1))), "g0"),
    (dict(kn=np.ones(2)), "kn"),
    (dict(kt=np.ones(3)), "kt"),
    (dict(K=np.eye(4)), "K"),
    (dict(method="mortar"), "method"),
    (dict(kn=None), "kn"),
])
def test_bad_arguments_raise(change, name):
    system = floating_pair([1.0, 2.0], 3.0, 1.0, 0.0)
    args = dict(K=system.K, f=system.f, G=system.G, g0=system.g0, kn=10.0, kt=0.0)
    args.update(change)
    with pytest.raises(ValueError, match=name):
        solve_static_contact(**args)


def test_lagrange_falls_back_to_augmented_lagrangian(monkeypatch):
    """If the active-set Newton fails (cycling, singular, budget), the Uzawa iteration on
    penalty sub-problems reaches the same exact solution."""
    system = two_blocks(gap=lambda x, y: 0.1 * ((x - 0.5) ** 2 + (y - 0.5) ** 2))
    args = (system.K, system.f, system.G, system.g0, None, KT)
    reference = solve_static_contact(*args, method="lagrange")

    def failing(space, g0, s, mu, tol_abs, max_iter):
        return static._Outcome(mu, 1, static.NOT_CONVERGED, "active set cycling")

    monkeypatch.setattr(static, "_active_set", failing)
    r = solve_static_contact(*args, method="lagrange")
    assert r.status == 0, r.reason
    assert r.iterations > reference.iterations
    np.testing.assert_array_equal(r.in_contact, reference.in_contact)
    np.testing.assert_allclose(r.N0, reference.N0, rtol=1e-8, atol=1e-10 * r.N0.max())
    assert r.complementarity <= 1e-12


def test_active_set_detects_cycling():
    """A repeated active set (here: a start that already is the PDAS fixed point, with an
    unreachable tolerance) is reported as cycling instead of looping to max_iter."""
    system = two_blocks(gap=lambda x, y: 0.1 * ((x - 0.5) ** 2 + (y - 0.5) ** 2))
    K, f, G, g0, kn, kt = static._check_shapes(system.K, system.f, system.G, system.g0,
                                               KN, KT, "lagrange")
    space = static._ContactSpace(K, f, G, kn, kt)
    space.tolerance = lambda tol_abs, *terms: -1.0  # nothing ever converges
    out = static._active_set(space, g0, kn, space.start(g0, kn), -1.0, 50)
    assert out.status == static.NOT_CONVERGED and "cycling" in out.reason
    assert out.iterations < 10
