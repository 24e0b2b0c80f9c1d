"""Where the contact pairs of a static state (``static.nc``: pair positions x, y, z at rest, m) sit on
the ring's upper surface, the sector centred on the X axis (θ = atan2(y, x) ∈ [-θ_h, θ_h])."""
from __future__ import annotations

import numpy as np
import xarray as xr


def surface_coords(static: xr.Dataset) -> tuple[np.ndarray, np.ndarray]:
    """Per pair: circumferential arc position s = r θ from the sector centre (m, r = √(x² + y²)) and
    axial position z (m)."""
    theta = np.arctan2(static.y.values, static.x.values)
    radius = np.hypot(static.x.values, static.y.values)
    return radius * theta, static.z.values


def sector_position(static: xr.Dataset, half_angle: float) -> np.ndarray:
    """Per pair: |θ| / θ_h ∈ [0, 1] (0 under the blade, 1 on the sector boundaries), ``half_angle`` θ_h
    = π / N in rad."""
    return np.abs(np.arctan2(static.y.values, static.x.values)) / half_angle
