"""Ring shape parametrisation (paper §3.1.1, Table 2; docs/design.md §2 "Shape parameters").

kappa_i in [-1, 1] maps piecewise-linearly to the radial offset delta_r of a bump's central node:
kappa = -1, 0, +1 -> offsets[0], 0, offsets[2]. A bump is the C^1 uniform quadratic B-spline on
4 equally spaced knots, scaled to unit height (zero value and slope at both ends):

    B(s) = s^2/2 (0<=s<1),  (-2s^2 + 6s - 3)/2 (1<=s<2),  (3-s)^2/2 (2<=s<=3),  max B = 3/4.

Upper surface: one bump over the whole sector [-theta_h, theta_h] (kappa1, +delta_r outward).
Lower surface: three bumps of width 2 theta_h / 3 centred at -2/3, 0, +2/3 theta_h (kappa2 on the
two outer ones, kappa3 on the central one); +delta_r moves the lower surface outward (removes
material, a hollow), -delta_r adds material (a bump).
"""

from __future__ import annotations

import numpy as np

KAPPA_RANGE = (-1.0, 1.0)


def check_kappa(kappa) -> np.ndarray:
    """Return kappa as a float array of 3, or raise ValueError naming the bad component."""
    k = np.asarray(kappa, dtype=float)
    if k.shape != (3,):
        raise ValueError(f"kappa must have 3 components (kappa1, kappa2, kappa3), got shape {k.shape}")
    for i, value in enumerate(k, start=1):
        if not (KAPPA_RANGE[0] <= value <= KAPPA_RANGE[1]):
            raise ValueError(f"kappa{i} = {float(value)!r} is out of range: allowed [-1, 1]")
    return k


def kappa_to_offset(kappa: float, offsets) -> float:
    """Table 2 mapping: piecewise-linear interpolation through (-1, o0), (0, 0), (1, o2)."""
    return float(np.interp(kappa, [-1.0, 0.0, 1.0], offsets))


def unit_bump(s) -> np.ndarray:
    """Unit-height quadratic B-spline bump of the normalised coordinate s in [-1, 1] (0 outside)."""
    u = 1.5 * (np.asarray(s, dtype=float) + 1.0)  # knots 0, 1, 2, 3
    b = np.where(u < 1.0, 0.5 * u**2,
                 np.where(u < 2.0, 0.5 * (-2.0 * u**2 + 6.0 * u - 3.0), 0.5 * (3.0 - u) ** 2))
    return np.where((u < 0.0) | (u > 3.0), 0.0, b / 0.75)


def upper_offset(theta, half_angle: float, delta1: float) -> np.ndarray:
    """delta_r of the ring's upper (contact) surface at angle theta (rad)."""
    return delta1 * unit_bump(np.asarray(theta) / half_angle)


def lower_offset(theta, half_angle: float, delta2: float, delta3: float) -> np.ndarray:
    """delta_r of the ring's lower surface: side bumps (delta2) at +-2/3 theta_h, central (delta3)."""
    s = np.asarray(theta) / half_angle  # in [-1, 1]; each bump has half-width 1/3
    return (delta2 * (unit_bump(3.0 * (s + 2.0 / 3.0)) + unit_bump(3.0 * (s - 2.0 / 3.0)))
            + delta3 * unit_bump(3.0 * s))


def shape_offsets(kappa, shape_cfg: dict) -> tuple[float, float, float]:
    """(delta1, delta2, delta3) in metres for a validated kappa."""
    k = check_kappa(kappa)
    return tuple(kappa_to_offset(k[i], shape_cfg[f"kappa{i + 1}_offsets"]) for i in range(3))


def unit_bump_slope(s) -> np.ndarray:
    """d(unit_bump)/ds."""
    u = 1.5 * (np.asarray(s, dtype=float) + 1.0)
    du = np.where(u < 1.0, u, np.where(u < 2.0, -2.0 * u + 3.0, -(3.0 - u)))
    return np.where((u < 0.0) | (u > 3.0), 0.0, 1.5 * du / 0.75)


def upper_slope(theta, half_angle: float, delta1: float) -> np.ndarray:
    """d(upper_offset)/d(theta) (m/rad), for the contact normals."""
    return delta1 * unit_bump_slope(np.asarray(theta) / half_angle) / half_angle
