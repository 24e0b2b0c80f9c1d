"""Seeded spring–mass chains with Jenkins elements: the randomised family on which the continuation
drivers are tested (``tests/nonlinear/test_continuation_family.py``) and the EPMC is checked in the
time domain (:mod:`ringdamper.studies.epmc_time_domain`; docs/nonlinear_core.md §4.2, §4.4).

Strong, strongly non-proportional friction (kt 5–30 against springs 0.4–1.2): the EPMC backbones of
the family fold in α, often twice, and turn at stick–slip corners.
"""
from functools import lru_cache

import numpy as np

from ringdamper.nonlinear.contact.friction import FrictionContacts
from ringdamper.nonlinear.harmonic_balance.epmc import linear_limit
from ringdamper.nonlinear.harmonic_balance.structure import Structure

SEEDS = range(200)
"""The family's seeds."""
OPTIONS = dict(H=1, nt=64, tol=1e-5)
"""The family's EPMC settings (harmonics, AFT samples, solver tolerance)."""
ISSUE_GRID = 10 ** np.arange(-1.5, 1.51, 0.25)
"""The amplitude grid of :func:`issue_chain`."""


def jenkins_chain(seed: int, H: int = 1):
    """Random fixed–fixed spring–mass chain (1–5 masses, ground springs at both ends) with 1–3
    Jenkins elements at constant normal load, each between a mass and the ground or between two
    neighbouring masses (``numpy.random.default_rng(seed)``; springs 0.4–1.2, masses 0.8–1.8,
    kt 5–30, preloads N0 0.3–2.0, μ = 1, kn = 1: strong, strongly non-proportional friction).
    Forced at the first mass, observed at the last."""
    rng = np.random.default_rng(seed)
    n = int(rng.integers(1, 6))
    springs = rng.uniform(0.4, 1.2, n + 1)
    M = np.diag(rng.uniform(0.8, 1.8, n))
    K = np.diag(springs[:-1] + springs[1:]) - np.diag(springs[1:-1], -1) - np.diag(springs[1:-1], 1)
    rows = []
    for _ in range(int(rng.integers(1, 4))):
        w = np.zeros(n)
        i = int(rng.integers(0, n))
        w[i] = 1.0
        if i > 0 and rng.random() < 0.5:                     # between masses i − 1 and i
            w[i - 1] = -1.0
        rows += [np.zeros(n), w, np.zeros(n)]
    npairs = len(rows) // 3
    st = Structure.real(M, K, np.array(rows), np.eye(n)[-1], np.eye(n)[0], H=H)
    contacts = FrictionContacts(kn=np.ones(npairs), kt=rng.uniform(5.0, 30.0, npairs), mu=1.0,
                                N0=rng.uniform(0.3, 2.0, npairs), gap=0.0)
    return st, contacts


def chain_grid(st, c, lo=-0.15, hi=0.65, n=6):
    """Amplitudes from just below the first slip (``linear_limit`` of the stuck mode) to 10^hi
    times it, log-spaced: the range where the family's backbones fold."""
    _, phi = st.stuck_modes(c.stuck_stiffness().ravel())
    return linear_limit(st, c, phi[:, 0]) * np.logspace(lo, hi, n)


@lru_cache(maxsize=1)
def issue_chain():
    """A 3-DoF chain with two Jenkins elements whose backbone (H = 1, :data:`ISSUE_GRID`) folds
    twice in α at a tight fold: arc-length steps that cross the fold land on a branch of higher
    frequency (ω 0.997 → 1.104) that walks back to α ≈ 1e-45. Forced at mass 2, observed at
    mass 3."""
    ki = np.array([0.5, 0.6, 1.1, 0.8])
    M = np.diag([1.5, 1.2, 1.7])
    K = np.diag(ki[:-1] + ki[1:]) - np.diag(ki[1:-1], -1) - np.diag(ki[1:-1], 1)
    w1, w2 = np.array([1, 0, 0.]), np.array([-1, 1, 0.])
    B = np.array([0 * w1, w1, 0 * w1, 0 * w2, w2, 0 * w2])
    c = FrictionContacts(kn=[1., 1.], kt=[24., 16.], mu=1.0, N0=[0.6, 1.8], gap=0.0)
    st = Structure.real(M, K, B, response=np.array([0, 0, 1.]), force=np.array([0, 1, 0.]), H=1)
    return st, c
