"""The linear part of the contact law, in one place (paper §2.5.2; docs/design.md, *Contact*).

Per node-to-node pair of tributary area A: normal and tangential stiffness kn = k_n'' A and
kt = k_t'' A (``contact.normal_stiffness_per_area``, ``contact.tangential_stiffness_per_area``,
N/m^3). The static solve uses them as they are (penalty normal law, sticking tangential springs).

The *stuck linearisation* (the contact at rest, every slider stuck) puts springs (kn, kt, kt) in the
local directions (n, t1, t2) of every closed pair (preloaded, N0 > 0) and nothing on open pairs; the
tangential springs exist only if the friction coefficient mu > 0 (without friction nothing holds
a pair tangentially). Every linearised stuck model of the package (FE modal analysis, reduced model,
friction element, EPMC start) uses :func:`stuck_springs`.
"""
from __future__ import annotations

import numpy as np


def pair_stiffness(area, contact_cfg: dict) -> tuple[np.ndarray, np.ndarray]:
    """(kn, kt) per pair (N/m): stiffness per unit area x tributary area ``area`` (m^2)."""
    area = np.asarray(area, dtype=float)
    return (contact_cfg["normal_stiffness_per_area"] * area,
            contact_cfg["tangential_stiffness_per_area"] * area)


def stuck_springs(kn, kt, mu, closed) -> tuple[np.ndarray, np.ndarray]:
    """(kn, kt) of the stuck linearisation: kn on ``closed`` pairs, kt on closed pairs where mu > 0,
    zero elsewhere (arrays broadcast to the number of pairs)."""
    kn, kt, mu, closed = np.broadcast_arrays(np.asarray(kn, float), np.asarray(kt, float),
                                             np.asarray(mu, float), np.asarray(closed, bool))
    return np.where(closed, kn, 0.0), np.where(closed & (mu > 0), kt, 0.0)


def stuck_pair_stiffness(area, contact_cfg: dict, closed=True) -> tuple[np.ndarray, np.ndarray]:
    """Stuck linearisation of the configured law on pairs of tributary ``area``; ``closed``
    (per pair, default all) marks the pairs in contact (N0 > 0)."""
    kn, kt = pair_stiffness(area, contact_cfg)
    return stuck_springs(kn, kt, contact_cfg["friction_coefficient"], closed)


def spring_diagonal(kn, kt, n_pairs: int) -> np.ndarray:
    """(n_pairs, 3) spring constants in the pair-major local directions (n, t1, t2): (kn, kt, kt)."""
    return np.column_stack([np.broadcast_to(kn, n_pairs), np.broadcast_to(kt, n_pairs),
                            np.broadcast_to(kt, n_pairs)])
