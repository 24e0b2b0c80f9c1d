"""Closure of the contact pairs in a static state (``static.nc``): d_n = initial gap − gap, the
normal approach of a pair's two surfaces under the load, per pair and averaged per station."""
from __future__ import annotations

import numpy as np
import xarray as xr


def pair_closure(static: xr.Dataset) -> np.ndarray:
    """Closure d_n = initial gap − gap (m) of every pair."""
    return static.initial_gap.values - static.gap.values


def station_means(static: xr.Dataset, coordinate: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(distinct values of ``coordinate`` (per pair, rounded to 1e-9), mean closure d_n (m) of the
    pairs at each)."""
    stations, station = np.unique(np.round(coordinate, 9), return_inverse=True)
    return stations, np.bincount(station, pair_closure(static)) / np.bincount(station)
