"""Scalar summary of a backbone, for comparisons (surrogate against computed, ours against the
paper): the maximum modal damping ratio ζ_max, the amplitude |q_res,z| and normalised frequency ω0
there, and ω0 at the lowest and highest amplitude of the usable backbone.

ζ_max is the maximum of ζ along a backbone up to a |q_res,z| limit, read in one of two ways:
:func:`grid_zeta_max`, the largest sampled value (a grid node), and :func:`log_q_zeta_max`, the
largest sampled value refined by a parabola in ln|q_res,z| (between grid nodes)."""
from __future__ import annotations

import numpy as np

from ..status import usable_status


def grid_zeta_max(q, zeta, q_max: float = np.inf):
    """ζ_max as sampled: the largest ζ over the amplitude-grid nodes (axis 0) with |q_res,z| ≤
    ``q_max`` (every node when ``q_max`` is infinite), and the index of the node reaching it (the
    first on a tie). The result is a grid value, never one between nodes (the maximum of the
    piecewise-linear backbone). ``q``, ``zeta``: (amplitude,) for one backbone, (amplitude, point)
    for many; a NaN ζ in the range gives NaN."""
    z = zeta if np.isinf(q_max) else np.where(q <= q_max, zeta, -np.inf)
    j = np.argmax(z, axis=0)
    return np.take_along_axis(z, j[None], 0)[0], j


def log_q_zeta_max(q, zeta, q_max: float = np.inf) -> tuple[float, float]:
    """(|q_res,z| at ζ_max, ζ_max) with ζ_max interpolated in ln|q_res,z|: over the points with
    |q_res,z| ≤ ``q_max``, the largest ζ refined by the vertex of the parabola through it and its two
    neighbours (in the order given) in (ln q, ζ), the vertex kept between those neighbours. The grid
    point itself where the largest ζ is an end point or the three points are not concave. Unlike
    :func:`grid_zeta_max` the peak may lie between grid nodes: a coarse α grid is read closer to
    the backbone's own peak."""
    below = q <= q_max
    x, y = np.log(q[below]), zeta[below]
    i = int(np.argmax(y))
    if i == 0 or i == len(y) - 1:
        return float(np.exp(x[i])), float(y[i])
    a, b, c = np.polyfit(x[i - 1:i + 2], y[i - 1:i + 2], 2)
    if a >= 0:
        return float(np.exp(x[i])), float(y[i])
    xv = float(np.clip(-b / (2 * a), x[i - 1], x[i + 1]))
    return float(np.exp(xv)), float(np.polyval([a, b, c], xv))


def backbone_summary(q, omega0, zeta, status=None, max_level=np.inf) -> dict:
    """``zeta_max``, ``q_at_zeta_max`` [m], ``omega0_at_zeta_max``, ``omega0_low`` and
    ``omega0_high`` (first and last finite points) of a backbone given on one amplitude grid;
    points whose ``status`` is not usable (0 or 3) or not finite are left out. ζ_max is sought
    where |q_res,z| ≤ ``max_level`` [m] (the optimum criterion's range, ``exploration.optimum_max_level``)
    as :func:`grid_zeta_max`, so that a prediction and a computation are summarised by the same rule."""
    q, omega0, zeta = (np.asarray(a, float) for a in (q, omega0, zeta))
    ok = np.isfinite(q) & np.isfinite(omega0) & np.isfinite(zeta)
    if status is not None:
        ok &= usable_status(status)
    if not ok.any():
        raise ValueError("the backbone has no usable point")
    idx = np.flatnonzero(ok)
    if not np.any(q[idx] <= max_level):
        raise ValueError(f"the backbone has no usable point with |q_res,z| <= {max_level} m")
    i = grid_zeta_max(q, np.where(ok, zeta, -np.inf), max_level)[1]
    return {"zeta_max": float(zeta[i]), "q_at_zeta_max": float(q[i]),
            "omega0_at_zeta_max": float(omega0[i]), "omega0_low": float(omega0[idx[0]]),
            "omega0_high": float(omega0[idx[-1]]), "q_high": float(q[idx[-1]])}


def dnnm_summary(ds, max_level=np.inf) -> dict:
    """:func:`backbone_summary` of a ``dnnm.nc`` dataset."""
    return backbone_summary(ds.q_res_z.values, ds.omega0.values, ds.zeta.values, ds.status.values,
                            max_level)
