"""What users read off a backbone (dnnm.nc), and errors against a reference.

From the converged points (status 0 or 3) of a backbone, in order of amplitude:

* ``zeta_max`` and ``q_at_zeta_max``: the peak of zeta interpolated in log |q_res,z| up to
  ``max_level`` (``exploration.optimum_max_level``, where the campaign's optimum reads it),
  :func:`ringdamper.campaign.summary.log_q_zeta_max`;
* ``freq_low`` / ``freq_high``: the resonant frequency (Hz) at the first and the last of the
  response levels (``sensitivity.levels``), linear in log |q_res,z|;
* ``q_gamma_<i>``: |q_res,z| (m) at forcing level gamma_i, on the backbone's first rise of gamma
  (linear in gamma), the Table 3 levels.

A level outside the backbone gives NaN, which counts as an infinite error.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from ...campaign.summary import log_q_zeta_max
from ...status import usable_status


def _usable(ds: xr.Dataset):
    ok = usable_status(ds.status.values) & np.isfinite(ds.q_res_z.values) & np.isfinite(ds.zeta.values)
    return {k: ds[k].values[ok] for k in ("q_res_z", "zeta", "frequency", "gamma")}


def _interp(x_new: float, x: np.ndarray, y: np.ndarray) -> float:
    if len(x) < 2 or not x[0] <= x_new <= x[-1]:
        return np.nan
    return float(np.interp(x_new, x, y))


def _first_rise(g: np.ndarray) -> int:
    """Length of the leading strictly increasing run of g."""
    d = np.flatnonzero(np.diff(g) <= 0)
    return len(g) if len(d) == 0 else int(d[0]) + 1


def gamma_at(ds: xr.Dataset, levels) -> np.ndarray:
    """Forcing gamma (N) at which the backbone's |q_res,z| equals each level (m)."""
    b = _usable(ds)
    return np.array([_interp(np.log(lv), np.log(b["q_res_z"]), b["gamma"]) for lv in levels])


def user_quantities(ds: xr.Dataset, response_levels, gammas, max_level: float = np.inf) -> dict:
    """The quantities above as a flat dict (units: 1, m, Hz, Hz, m ...)."""
    b = _usable(ds)
    logq = np.log(b["q_res_z"])
    q_star, z = log_q_zeta_max(b["q_res_z"], b["zeta"], max_level)
    out = {"zeta_max": z, "q_at_zeta_max": q_star,
           "freq_low": _interp(np.log(response_levels[0]), logq, b["frequency"]),
           "freq_high": _interp(np.log(response_levels[-1]), logq, b["frequency"])}
    n = _first_rise(b["gamma"])
    for i, g in enumerate(gammas, start=1):
        out[f"q_gamma_{i}"] = _interp(g, b["gamma"][:n], b["q_res_z"][:n])
    return out


def relative_errors(values: dict, reference: dict) -> dict:
    """|value / reference - 1| per quantity (inf where either is NaN)."""
    out = {}
    for k, ref in reference.items():
        v = values[k]
        out[k] = abs(v / ref - 1.0) if np.isfinite(v) and np.isfinite(ref) and ref != 0 else np.inf
    return out


def richardson(h, f) -> tuple[float, float]:
    """(f at h -> 0, order p) of f(h) = f0 + C h^p through three (h, f) points, h decreasing: p solves
    (f1 - f2)/(f2 - f3) = (h1^p - h2^p)/(h2^p - h3^p) (Brent), then f0 = f3 - C h3^p. Raises when the
    sequence is not monotone (no asymptotic range)."""
    from scipy.optimize import brentq

    h, f = np.asarray(h, float), np.asarray(f, float)
    if h.shape != (3,) or not (h[0] > h[1] > h[2] > 0):
        raise ValueError(f"richardson needs three decreasing positive h, got {h}")
    ratio = (f[0] - f[1]) / (f[1] - f[2])
    if not np.isfinite(ratio) or ratio <= 0:
        raise ValueError(f"richardson: f = {f} is not monotone in h")

    def g(p):
        return (h[0] ** p - h[1] ** p) / (h[1] ** p - h[2] ** p) - ratio

    p = brentq(g, 0.05, 12.0)
    C = (f[1] - f[2]) / (h[1] ** p - h[2] ** p)
    return float(f[2] - C * h[2] ** p), float(p)
