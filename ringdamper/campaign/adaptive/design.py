"""The adaptive design's geometry: initial design, candidate sets, gids and the sample table.

The initial design holds the reference rings (the default ring, the six one-at-a-time extremes and the
paper's optimum, computed by every campaign anyway) and ``n_initial - 8`` maximin Latin-hypercube
points (:func:`~ringdamper.campaign.design_space.maximin_lhs`, away from the reference rings and the
validation rings). The validation rings are exactly those of the paper design: they are drawn from the
same seeded stream, after the paper's training points, so the honest check does not depend on the
design. Each round draws its own candidate set, a scrambled Sobol' sequence seeded by (seed, round),
without the points closer than ``sampling.min_distance`` to a validation ring.
"""
from __future__ import annotations

import re

import numpy as np
import pandas as pd
from scipy.spatial.distance import cdist
from scipy.stats import qmc

from ..design_space import (
    N_KAPPA,
    REFERENCE_RINGS,
    SAMPLE_COLUMNS,
    check_samples,
    check_separation,
    maximin_lhs,
    paper_design,
)

ROUND_GID = re.compile(r"^a(\d{2,})_(\d{3})$")  # gid of the i-th ring chosen in round k: a{k:02d}_{i:03d}
INITIAL_STREAM = 1  # the initial design's random stream, independent of the paper design's


def round_gid(round_: int, i: int) -> str:
    """gid of the ``i``-th ring (0-based) chosen in round ``round_`` (1-based)."""
    return f"a{round_:02d}_{i:03d}"


def round_of(gid: str) -> int | None:
    """The round that chose geometry ``gid``, None for a ring of the sample table."""
    match = ROUND_GID.match(gid)
    return int(match.group(1)) if match else None


def reference_kappa() -> np.ndarray:
    """(8, 3) the reference rings, in the order of REFERENCE_RINGS."""
    return np.array(list(REFERENCE_RINGS.values()), dtype=float)


def initial_entropy(sampling: dict) -> list[int]:
    """The seed of the initial design's LHS points: (``seed``, INITIAL_STREAM), followed by
    ``adaptive.initial_seed`` unless it is 0 (so that 0 is the default design, and any other value
    draws another initial design with the same validation rings, which ``seed`` draws)."""
    extra = sampling["adaptive"]["initial_seed"]
    return [sampling["seed"], INITIAL_STREAM, *([extra] if extra else [])]


def initial_design(sampling: dict, validation: np.ndarray) -> np.ndarray:
    """(n_initial, 3): the reference rings, then maximin LHS points away from them and ``validation``."""
    n_initial = sampling["adaptive"]["n_initial"]
    refs = reference_kappa()
    rng = np.random.default_rng(initial_entropy(sampling))
    lhs = maximin_lhs(n_initial - len(refs), np.vstack([refs, validation]), rng, sampling["lhs_candidates"])
    design = np.vstack([refs, lhs])
    check_separation(design, validation, sampling["min_distance"])
    return design


def adaptive_samples(sampling: dict) -> pd.DataFrame:
    """The sample table known before any round: the initial design (training, t000...) and the
    validation rings of the paper design (v000...). Every reference ring is in the initial design."""
    validation = paper_design(sampling)[1]
    training = initial_design(sampling, validation)
    rows = [(f"t{i:03d}", *k, "training") for i, k in enumerate(training)]
    rows += [(f"v{i:03d}", *k, "validation") for i, k in enumerate(validation)]
    return check_samples(pd.DataFrame(rows, columns=list(SAMPLE_COLUMNS)), "the adaptive initial design")


def with_rounds(samples: pd.DataFrame, records: list[dict]) -> pd.DataFrame:
    """The campaign's whole sample table: ``samples`` followed by the rings the round ``records`` chose
    (split training), in round order."""
    rows = [(c["gid"], *c["kappa"], "training") for record in records for c in record["chosen"]]
    table = pd.concat([samples, pd.DataFrame(rows, columns=list(SAMPLE_COLUMNS))], ignore_index=True)
    return check_samples(table, "the adaptive design")


def candidates(sampling: dict, round_: int, validation: np.ndarray) -> np.ndarray:
    """The candidate set of round ``round_``: ``n_candidates`` scrambled Sobol' points in [-1, 1]^3
    seeded by (seed, round), without those closer than ``min_distance`` to a validation ring."""
    n = sampling["adaptive"]["n_candidates"]
    sobol = qmc.Sobol(d=N_KAPPA, scramble=True, rng=np.random.default_rng([sampling["seed"], round_ + 1]))
    points = 2.0 * sobol.random_base2(int(np.ceil(np.log2(n))))[:n] - 1.0
    if len(validation):
        points = points[cdist(points, validation).min(axis=1) >= sampling["min_distance"]]
    return points
