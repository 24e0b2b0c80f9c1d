"""A user's structure and contact parameters are checked at construction: every message names the
argument, the shape expected and the shape given; parameters given once hold for every pair."""
import numpy as np
import pytest

from ringdamper.nonlinear.contact.friction import FrictionContacts
from ringdamper.nonlinear.harmonic_balance.epmc import epmc
from ringdamper.nonlinear.harmonic_balance.structure import Structure

from .systems import multi_dof

M, K = np.eye(2), np.array([[2.0, -1.0], [-1.0, 1.0]])
B = np.array([[0.0, 1.0], [1.0, 0.0], [0.0, 0.0]])
E = np.array([1.0, 0.0])


@pytest.mark.parametrize("argument, value, message", [
    ("M", np.eye(2)[:, :1], r"harmonic 0\.M: expected a square matrix \(n, n\), got shape \(2, 1\)"),
    ("K", np.eye(3), r"harmonic 0\.K: expected shape \(2, 2\) \(n = 2 DoFs, from M\), got \(3, 3\)"),
    ("B", np.eye(3), r"harmonic 0\.B: expected shape \(p, 2\) .*got \(3, 3\)"),
    ("B", np.zeros((4, 2)), r"B: expected 3 rows \(n, t1, t2\) per contact pair, got 4 rows"),
    ("response", np.ones(3), r"harmonic 0\.response: expected shape \(2,\) .*got \(3,\)"),
    ("force", np.ones((2, 1)), r"harmonic 1\.force: expected shape \(2,\) .*got \(2, 1\)"),
    ("C", np.eye(3), r"harmonic 0\.C: expected shape \(2, 2\) .*got \(3, 3\)"),
    ("zeta", np.ones(3), r"harmonic 0\.zeta: expected a scalar or shape \(2,\) .*got \(3,\)"),
    ("zeta", -0.1, r"harmonic 0\.zeta: modal damping ratios must be >= 0"),
])
def test_structure_names_the_argument_and_both_shapes(argument, value, message):
    args = {"M": M, "K": K, "B": B, "response": E, "force": E}
    extra = {}
    if argument in args:
        args[argument] = value
    else:
        extra[argument] = value
    with pytest.raises(ValueError, match=message):
        Structure.real(args["M"], args["K"], args["B"], args["response"], args["force"], H=1, **extra)


def test_contact_parameters_name_the_parameter():
    with pytest.raises(ValueError, match=r"FrictionContacts\.kn: expected a scalar or a 1-D array .* "
                                         r"got shape \(2, 2\)"):
        FrictionContacts(kn=np.ones((2, 2)), kt=1.0, mu=0.1, N0=1.0, gap=0.0)
    with pytest.raises(ValueError, match="disagree on the number of pairs: kn has 2, mu has 3"):
        FrictionContacts(kn=[1.0, 1.0], kt=1.0, mu=[0.1, 0.1, 0.1], N0=1.0, gap=0.0)


def test_per_pair_parameters_must_match_the_structure():
    st, _ = multi_dof(H=1)                                          # two pairs
    three = FrictionContacts(kn=[2e5] * 3, kt=1e5, mu=0.05, N0=30.0, gap=0.0)
    with pytest.raises(ValueError, match=r"parameters given for 3 contact pairs, the structure's B has "
                                         r"2 pairs \(6 rows"):
        epmc(st, three, np.array([1e-3]), H=1)


def test_scalar_parameters_hold_for_every_pair():
    st, _ = multi_dof(H=1)
    alpha = np.geomspace(1e-3, 3e-2, 4)
    scalars = epmc(st, FrictionContacts(kn=2e5, kt=1e5, mu=0.05, N0=30.0, gap=0.0), alpha, H=1)
    per_pair = epmc(st, FrictionContacts(kn=[2e5, 2e5], kt=[1e5, 1e5], mu=[0.05, 0.05], N0=[30.0, 30.0],
                                         gap=[0.0, 0.0]), alpha, H=1)
    np.testing.assert_array_equal(scalars.status, per_pair.status)
    np.testing.assert_array_equal(scalars.omega, per_pair.omega)
    np.testing.assert_array_equal(scalars.xi, per_pair.xi)
