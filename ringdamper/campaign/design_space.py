"""The normalised shape space kappa in [-1, 1]^3 and what every design of experiments is built from
(paper §3.2.2): the reference rings, maximin Latin-hypercube points, the paper's fixed design and the
sample table with its checks (:mod:`.sampling` makes the campaign's table from them).

Paper design: training set the full factorial {levels}^3 plus maximin Latin-hypercube points; validation
set the paper's named cases plus maximin LHS points. "Maximin" here: among ``lhs_candidates`` random LHS
designs (scipy.stats.qmc), keep the one whose smallest distance to itself and to the points already
chosen is largest (Morris & Mitchell 1995 criterion, brute-force search).
"""

from __future__ import annotations

import itertools

import numpy as np
import pandas as pd
from scipy.spatial.distance import cdist, pdist
from scipy.stats import qmc

N_KAPPA = 3

# Rings every campaign computes, for the figures and forced responses: the default, the six
# one-at-a-time extremes of Fig. 11 and the paper's optimum (§3.4).
REFERENCE_RINGS = {
    "default": (0.0, 0.0, 0.0),
    "kappa1=+1": (1.0, 0.0, 0.0), "kappa1=-1": (-1.0, 0.0, 0.0),
    "kappa2=+1": (0.0, 1.0, 0.0), "kappa2=-1": (0.0, -1.0, 0.0),
    "kappa3=+1": (0.0, 0.0, 1.0), "kappa3=-1": (0.0, 0.0, -1.0),
    "paper optimum": (1.0, -1.0, -1.0),
}


def _min_distance(points: np.ndarray, existing: np.ndarray) -> float:
    d = pdist(points).min() if len(points) > 1 else np.inf
    if len(existing):
        d = min(d, cdist(points, existing).min())
    return d


def maximin_lhs(n: int, existing: np.ndarray, rng: np.random.Generator, candidates: int) -> np.ndarray:
    """``n`` LHS points in [-1, 1]^3 maximising the minimum distance (to themselves and ``existing``)."""
    if n == 0:
        return np.empty((0, N_KAPPA))
    best, best_d = None, -np.inf
    for _ in range(candidates):
        u = qmc.LatinHypercube(d=N_KAPPA, rng=rng).random(n)
        pts = 2.0 * u - 1.0
        d = _min_distance(pts, existing)
        if d > best_d:
            best, best_d = pts, d
    return best


def paper_design(sampling: dict) -> tuple[np.ndarray, np.ndarray]:
    """(training, validation) kappa of the paper design: the factorial plus maximin LHS training
    points, then the named and maximin LHS validation points, from one seeded stream."""
    rng = np.random.default_rng(sampling["seed"])
    levels = sampling["factorial_levels"]
    factorial = np.array(list(itertools.product(levels, repeat=N_KAPPA)), dtype=float)
    train_lhs = maximin_lhs(sampling["n_lhs_training"], factorial, rng, sampling["lhs_candidates"])
    training = np.vstack([factorial, train_lhs])
    named = np.array(sampling["named_validation"], dtype=float).reshape(-1, N_KAPPA)
    val_lhs = maximin_lhs(sampling["n_lhs_validation"], np.vstack([training, named]), rng,
                          sampling["lhs_candidates"])
    validation = np.vstack([named, val_lhs])
    check_separation(training, validation, sampling["min_distance"])
    return training, validation


SAMPLE_COLUMNS = ("gid", "kappa1", "kappa2", "kappa3", "split")
SPLITS = ("training", "validation", "reference")


def check_samples(samples: pd.DataFrame, source: str = "samples.csv") -> pd.DataFrame:
    """The sample table, checked before any work is spent on it: the columns of
    :data:`SAMPLE_COLUMNS`, unique gids, finite kappa_i in [-1, 1], split one of :data:`SPLITS`.
    Raises ``ValueError`` naming ``source``, the row (0-based, header excluded), the field and the
    allowed range."""
    missing = [c for c in SAMPLE_COLUMNS if c not in samples.columns]
    if missing:
        raise ValueError(f"{source}: missing column(s) {missing}; expected columns {list(SAMPLE_COLUMNS)}")
    duplicated = samples.gid[samples.gid.duplicated(keep=False)]
    if len(duplicated):
        gid = duplicated.iloc[0]
        rows = list(duplicated.index[duplicated == gid])
        raise ValueError(f"{source}: gid {gid!r} appears in rows {rows}; every gid must be unique")
    for i in range(1, N_KAPPA + 1):
        col = f"kappa{i}"
        k = pd.to_numeric(samples[col], errors="coerce").to_numpy(float)
        bad = np.flatnonzero(~((k >= -1.0) & (k <= 1.0)))
        if bad.size:
            r = samples.index[bad[0]]
            raise ValueError(f"{source} row {r} (gid {samples.gid.loc[r]!r}): {col} = "
                             f"{samples[col].loc[r]} is outside the allowed range [-1, 1]")
    bad = ~samples.split.isin(SPLITS)
    if bad.any():
        r = samples.index[bad][0]
        raise ValueError(f"{source} row {r} (gid {samples.gid.loc[r]!r}): split = {samples.split.loc[r]!r}, "
                         f"allowed {list(SPLITS)}")
    return samples


def read_samples(path) -> pd.DataFrame:
    """samples.csv, checked by :func:`check_samples`."""
    return check_samples(pd.read_csv(path, dtype={"gid": str, "split": str}), str(path))


def check_separation(training: np.ndarray, validation: np.ndarray, min_distance: float) -> None:
    """Raise if two samples coincide (closer than ``min_distance``) anywhere in the design."""
    everything = np.vstack([training, validation])
    d = _min_distance(everything, np.empty((0, N_KAPPA)))
    if d < min_distance:
        raise ValueError(f"two samples are {d:.3g} apart, below sampling.min_distance = {min_distance}")
