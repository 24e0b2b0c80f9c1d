"""The travelling-wave convention of an engine-order excitation (DESIGN §3.3–3.4), in one place.

Engine order EO on N sectors: harmonic h of sector j equals harmonic h of the reference sector times
e^{i sigma_h j}, sigma_h = -2 pi h EO / N, i.e. the sector fields obey u_{j+1} = e^{i sigma_h} u_j
(Mead's cyclic constraint with that phase). Harmonic h lives in nodal diameter h EO mod N (folded
to 0..N/2); h = 0 is ND 0 (real).
"""
from __future__ import annotations

import numpy as np


def interblade_phase(h: int, n_sectors: int, engine_order: int) -> float:
    """sigma_h = -2 pi h EO / N wrapped to (-pi, pi]."""
    s = -2.0 * np.pi * ((h * engine_order) % n_sectors) / n_sectors
    return float(s + 2.0 * np.pi if s <= -np.pi else s)


def nodal_diameter(h: int, n_sectors: int, engine_order: int) -> int:
    """Nodal diameter of harmonic h: min(k, N - k) with k = h EO mod N."""
    k = (h * engine_order) % n_sectors
    return int(min(k, n_sectors - k))
