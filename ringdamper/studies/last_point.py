"""Why the campaign's backbones rise at the top of the amplitude grid (docs/investigations/last_point.md).

On the default ring γ and ζ jump between the last two grid amplitudes (α = 2.46e-4 → 3.0e-4 kg^½ m).
The study tells a physical change of the contact state from a numerical artefact: it traces the
default ring's backbone twice, at the campaign's harmonics on the campaign grid and at more
harmonics on a fine grid over the top of the range, with the separation indicators every dnnm.nc
carries (:mod:`ringdamper.nonlinear.indicators.separation`): n_min(α), the smallest unclipped normal force over
the period relative to its preload (1 stuck, crossing 0 where the first pair lifts off), and the
number of lifting pairs. A rise that starts where n_min crosses
0, and that a finer grid and more harmonics follow smoothly, is the onset of separation; a rise
with n_min well above 0, or one the fine grid does not reproduce, would be a branch jump.
"""
from __future__ import annotations

import numpy as np
import xarray as xr

from ringdamper.io import declared_dataset, variable
from ringdamper.nonlinear.indicators.separation import separation_indicators
from ringdamper.nonlinear.stage import DNNM_VARIABLES, STATUS_MEANING, amplitude_grid, solve_backbone
from ringdamper.status import usable_status


def fine_grid(campaign_alpha: np.ndarray, points_below: int, n_points: int) -> np.ndarray:
    """``n_points`` log-spaced amplitudes from the campaign grid value ``points_below`` points below
    its top to its top."""
    return np.geomspace(campaign_alpha[-1 - points_below], campaign_alpha[-1], n_points)


#: The variables of a trace: those of dnnm.nc it shares, the separation indicators included.
TRACE_VARIABLES = {name: DNNM_VARIABLES[name] for name in
                   ("frequency", "zeta", "gamma", "q_res_z", "normal_force_ratio_min", "lifting_pairs")}


def trace(reduced: xr.Dataset, static: xr.Dataset, config: dict, target_hz: float, alpha: np.ndarray,
          n_harmonics: int) -> xr.Dataset:
    """Backbone of the target mode at ``n_harmonics`` on ``alpha``: status, frequency, ζ, γ, |q_res,z|,
    n_min and the number of open pairs per amplitude."""
    backbone, contacts, res, _ = solve_backbone(reduced, static, config, target_hz, alpha, n_harmonics)
    usable = usable_status(res.status)
    n_min, lifting = separation_indicators(backbone, contacts, usable)
    values = {"frequency": res.frequency, "zeta": res.zeta, "gamma": res.gamma, "q_res_z": res.q_res_peak,
              "normal_force_ratio_min": n_min, "lifting_pairs": lifting}
    coords = {"amplitude": variable("amplitude", alpha, "kg0.5 m", "modal amplitude alpha")}
    ds = declared_dataset("last-point trace", TRACE_VARIABLES, values, coords, {"n_harmonics": n_harmonics})
    ds["status"] = variable("amplitude", np.asarray(res.status, np.int8), "1", STATUS_MEANING)
    return ds


def run_study(reduced: xr.Dataset, static: xr.Dataset, config: dict, target_hz: float) -> dict[str, xr.Dataset]:
    """The two traces of the study (``studies.last_point`` of the configuration): ``campaign`` at
    the campaign's H on its grid, ``fine`` at ``n_harmonics`` on :func:`fine_grid`."""
    study = config["studies"]["last_point"]
    alpha = amplitude_grid(config["dnnm"])
    if study["points_below"] >= alpha.size:
        raise ValueError(f"studies.last_point.points_below = {study['points_below']} must be below "
                         f"dnnm.n_amplitudes = {alpha.size}")
    fine = fine_grid(alpha, study["points_below"], study["n_points"])
    return {"campaign": trace(reduced, static, config, target_hz, alpha, config["dnnm"]["n_harmonics"]),
            "fine": trace(reduced, static, config, target_hz, fine, study["n_harmonics"])}


def onset_of_separation(trace_ds: xr.Dataset) -> float:
    """Amplitude where ``normal_force_ratio_min`` first crosses 0 (linear in log α between the
    bracketing points; NaN if it never does)."""
    a = np.log(trace_ds.amplitude.values)
    n = trace_ds.normal_force_ratio_min.values
    for k in range(len(a) - 1):
        if np.isfinite(n[k]) and np.isfinite(n[k + 1]) and n[k] > 0 >= n[k + 1]:
            return float(np.exp(a[k] + (a[k + 1] - a[k]) * n[k] / (n[k] - n[k + 1])))
    return float("nan")
