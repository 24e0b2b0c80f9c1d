"""Batch spread by a distance rule: the rings of a batch are picked greedily by decreasing acquisition
score, each at least ``spacing`` (normalised kappa units, Euclidean) from every training ring and every
ring already in the batch. The rule needs no model, so it holds for any surrogate, and it is cheap and
deterministic. If fewer than ``b`` candidates satisfy it, the spacing is halved until ``b`` do.
"""
from __future__ import annotations

import numpy as np
from scipy.spatial.distance import cdist


def select_batch(points: np.ndarray, score: np.ndarray, existing: np.ndarray, b: int,
                 spacing: float) -> np.ndarray:
    """Indices into ``points`` of the ``b`` rings of the batch (module docstring), best first."""
    order = np.argsort(-score, kind="stable")
    d_existing = cdist(points, existing).min(axis=1) if len(existing) else np.full(len(points), np.inf)
    b = min(b, len(points))
    while True:
        chosen = []
        nearest = d_existing.copy()
        for i in order:
            if nearest[i] >= spacing:
                chosen.append(i)
                if len(chosen) == b:
                    return np.array(chosen)
                nearest = np.minimum(nearest, np.linalg.norm(points - points[i], axis=1))
        spacing /= 2.0
