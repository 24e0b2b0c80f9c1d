"""Validation of the Kriging surrogates on the held-out geometries (paper §3.2.2, Fig. 13).

Per output, over every usable (geometry, amplitude) point of the validation split:

* R^2 = 1 - sum (y - y_hat)^2 / sum (y - mean y)^2 -- the paper's pooled view of Fig. 13a-d. Pooled
  over amplitudes, the variance of |q_res,z| and gamma is mostly their growth with alpha, which any
  model of the amplitude alone would capture; hence also
* R^2 within amplitudes: the same with sum (y - mean_alpha y)^2 about each amplitude's mean, which
  measures what the surrogate adds: the effect of the geometry;
* RMSE, maximum absolute error, and the coverage of the 95.45 % predictive band (the fraction of
  points with lower <= y <= upper; for the identity transform the band is y_hat +- 2 sigma, for the
  log transform its back-transform, :mod:`~ringdamper.campaign.kriging.transform`), the band widened
  by the round-off 1e-12 max|y| the fit takes as 0 (zeta = +-1e-17 at a stuck point whose model is
  the constant 0 is covered);

y_hat is the surrogate's point prediction, the median (the Kriging mean for the identity transform).
* Q^2: the same two R^2 of the leave-one-out predictions on the training set.
"""
from __future__ import annotations

import numpy as np
import xarray as xr

from ..io import variable
from .dataset import flagged_truncations, kappa
from .exploration import BACKBONE_OUTPUTS, backbones
from .kriging import BAND_PROBABILITY, CONSTANT_RTOL, SIGMA_BAND


def r2(y, y_hat, centre=None) -> float:
    """1 - SS_res / SS_tot with SS_tot about ``centre`` (default: the mean of y)."""
    y, y_hat = np.asarray(y, float), np.asarray(y_hat, float)
    centre = y.mean() if centre is None else centre
    return float(1.0 - np.sum((y - y_hat) ** 2) / np.sum((y - centre) ** 2))


def metrics(y, y_hat, lower, upper, group, atol: float = 0.0) -> dict:
    """Validation metrics of paired samples (1-D arrays) with the predictive band [``lower``,
    ``upper``], widened by the round-off ``atol``; ``group`` labels the amplitude of each sample (for
    the within-amplitude R^2)."""
    y, y_hat, lower, upper, group = map(np.asarray, (y, y_hat, lower, upper, group))
    means = {g: y[group == g].mean() for g in np.unique(group)}
    centre = np.array([means[g] for g in group])
    err = np.abs(y - y_hat)
    return {"r2": r2(y, y_hat), "r2_within": r2(y, y_hat, centre),
            "rmse": float(np.sqrt(np.mean(err ** 2))), "max_error": float(err.max()),
            "coverage": float(np.mean((lower - atol <= y) & (y <= upper + atol))), "n_points": int(y.size)}


def _paired(dataset: xr.Dataset, mask: xr.DataArray, name: str, mean: np.ndarray):
    """Computed and predicted values (and amplitude index) at the usable points; ``mean`` is
    (amplitude, geometry) like the Kriging prediction."""
    ok = mask.values.T
    y = dataset[name].values.T
    group = np.broadcast_to(np.arange(ok.shape[0])[:, None], ok.shape)
    return y[ok], mean[ok], group[ok], ok


def loo_pairs(fit: xr.Dataset, name: str):
    """Training values, their leave-one-out predictions and amplitude index (1-D arrays) of output
    ``name`` from kriging.nc (``<name>`` and ``<name>_loo_residual``, amplitude x geometry)."""
    y = fit[name].transpose("amplitude", "geometry").values
    e = fit[f"{name}_loo_residual"].transpose("amplitude", "geometry").values
    ok = np.isfinite(y) & np.isfinite(e)
    group = np.broadcast_to(np.arange(y.shape[0])[:, None], y.shape)
    return y[ok], (y - e)[ok], group[ok]


def validate(fit: xr.Dataset, surrogate, dataset: xr.Dataset, mask: xr.DataArray) -> xr.Dataset:
    """validation.nc: per output the metrics on the validation split and Q^2 (leave-one-out on the
    training split, from kriging.nc ``fit``), with the validation predictions of ``surrogate`` (median,
    spread, band) for the figures, the validation points' ``truncation_flag`` and the attribute
    ``flagged_truncations`` naming every ring's flagged points (:func:`flagged_truncations`)."""
    val = (dataset.split == "validation").values
    vset, vmask = dataset.isel(geometry=val), mask.isel(geometry=val)
    bb = backbones(surrogate, kappa(vset))
    rows = {k: [] for k in ("r2", "r2_within", "rmse", "max_error", "coverage", "n_points", "q2",
                            "q2_within")}
    for name in BACKBONE_OUTPUTS:
        y, y_hat, group, _ = _paired(vset, vmask, name, bb.mean[name])
        _, lower, _, _ = _paired(vset, vmask, name, bb.lower[name])
        _, upper, _, _ = _paired(vset, vmask, name, bb.upper[name])
        m = metrics(y, y_hat, lower, upper, group, CONSTANT_RTOL * float(np.nanmax(np.abs(fit[name].values))))
        ly, lhat, lgroup = loo_pairs(fit, name)
        lm = metrics(ly, lhat, lhat, lhat, lgroup)
        m["q2"], m["q2_within"] = lm["r2"], lm["r2_within"]
        for k in rows:
            rows[k].append(m[k])
    units = [dataset[name].attrs["units"] for name in BACKBONE_OUTPUTS]
    per_output = "units per output " + ", ".join(f"{n}: {u}" for n, u in zip(BACKBONE_OUTPUTS, units))
    data = {
        "r2": variable("output", rows["r2"], "1", "R2 on the validation points, pooled over amplitudes"),
        "r2_within": variable("output", rows["r2_within"], "1",
                              "R2 on the validation points about each amplitude's mean"),
        "q2": variable("output", rows["q2"], "1", "Q2: R2 of the leave-one-out predictions of the training set"),
        "q2_within": variable("output", rows["q2_within"], "1",
                              "Q2 about each amplitude's mean (leave-one-out, training set)"),
        "rmse": variable("output", rows["rmse"], "; ".join(units), f"root-mean-square validation error ({per_output})"),
        "max_error": variable("output", rows["max_error"], "; ".join(units),
                              f"largest absolute validation error ({per_output})"),
        "coverage": variable("output", rows["coverage"], "1",
                             f"fraction of validation points within the {100 * BAND_PROBABILITY:g} % predictive band"),
        "n_points": variable("output", rows["n_points"], "1", "usable validation points"),
        "usable": variable(("geometry", "amplitude"), vmask.values.astype(np.int8), "1",
                           "1 where the computed point is usable"),
        "held": variable(("geometry", "amplitude"), vset.held.values, "1",
                         "1 where the ring is held by the gauge (status 3)"),
    }
    for name, u in zip(BACKBONE_OUTPUTS, units):
        label = dataset[name].attrs["long_name"]
        data[f"{name}_computed"] = variable(("geometry", "amplitude"), vset[name].values, u,
                                            f"{label}: dNNM + E-EBM")
        data[f"{name}_predicted"] = variable(("geometry", "amplitude"), bb.mean[name].T, u,
                                             f"{label}: Kriging median")
        data[f"{name}_std"] = variable(("geometry", "amplitude"), bb.std[name].T, u,
                                       f"{label}: Kriging predictive spread, (upper - lower) / 4")
        for side in ("lower", "upper"):
            data[f"{name}_{side}"] = variable(("geometry", "amplitude"), getattr(bb, side)[name].T, u,
                                              f"{label}: {side} bound of the 95.45 % Kriging band")
    coords = {"output": variable("output", np.array(BACKBONE_OUTPUTS, dtype=object), "1", "surrogate output"),
              "geometry": variable("geometry", vset.geometry.values, "1", "validation geometry id"),
              "amplitude": variable("amplitude", dataset.amplitude.values, "kg0.5 m", "modal amplitude alpha")}
    for i in (1, 2, 3):
        coords[f"kappa{i}"] = variable("geometry", vset[f"kappa{i}"].values, "1", f"shape parameter kappa{i}")
    if "truncation_flag" in vset:
        data["truncation_flag"] = variable(("geometry", "amplitude"), vset.truncation_flag.values, "1",
                                           vset.truncation_flag.attrs["long_name"])
    return xr.Dataset(data, coords=coords, attrs={"sigma_band": SIGMA_BAND, "band_probability": BAND_PROBABILITY,
                                                  "flagged_truncations": "; ".join(flagged_truncations(dataset))})


def named_gids(dataset: xr.Dataset, cases, tol: float = 1e-9) -> list:
    """gids of the validation geometries at the shape parameters ``cases`` (list of 3-lists);
    a case the design does not hold raises ValueError."""
    k = kappa(dataset)
    out = []
    for case in cases:
        hit = np.flatnonzero(np.all(np.abs(k - np.asarray(case, float)) < tol, axis=1))
        if hit.size == 0:
            raise ValueError(f"named validation case {list(case)} is not in the dataset")
        out.append(str(dataset.geometry.values[hit[0]]))
    return out


def metrics_table(val: xr.Dataset):
    """Validation metrics as a pandas table (one row per output, units of RMSE / max error)."""
    import pandas as pd

    units = val.rmse.attrs["units"].split("; ")
    table = pd.DataFrame({k: val[k].values for k in ("r2", "r2_within", "q2", "q2_within", "rmse",
                                                     "max_error", "coverage", "n_points")},
                         index=pd.Index(val.output.values, name="output"))
    table.insert(4, "units", units)
    return table
