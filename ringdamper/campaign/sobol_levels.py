"""Sobol indices of omega0, zeta, gamma read at response levels |q_res,z| (paper §3.3.3, §3.4.1; Figs.
18, 20), on the Kriging prediction (the median of the log-scale models).

The model of the study is :func:`~ringdamper.campaign.exploration.level_function`: kappa -> the
predicted backbone of kappa read at each level. Its indices come from the pick-freeze estimators of
:func:`~ringdamper.campaign.sensitivity.sobol_indices` (one column per output and level, so one
design serves all of them), and, for the cross-check, from a polynomial chaos expansion of the same
function (:func:`~ringdamper.campaign.sensitivity.sobol_indices_pce`). Results are reshaped to
``output x parameter x level``.
"""
from __future__ import annotations

import numpy as np
import pandas as pd
import xarray as xr

from ..io import variable
from .exploration import ENVELOPE_OUTPUTS, level_function
from .sensitivity import sobol_indices, sobol_indices_pce

INDEX_VARIABLES = ("first_order", "total_order", "first_order_lower", "first_order_upper",
                   "total_order_lower", "total_order_upper")


def _by_level(ds: xr.Dataset, levels, outputs=ENVELOPE_OUTPUTS) -> xr.Dataset:
    """(output*level, parameter) indices of the level function -> (output, parameter, level)."""
    shape = (len(outputs), len(levels), ds.sizes["parameter"])
    data = {name: variable(("output", "parameter", "level"),
                           ds[name].values.reshape(shape).transpose(0, 2, 1), ds[name].attrs["units"],
                           ds[name].attrs["long_name"]) for name in INDEX_VARIABLES}
    for name in ("parameter_lower", "parameter_upper"):
        data[name] = (ds[name].dims, ds[name].values, ds[name].attrs)
    coords = {"output": variable("output", np.array(outputs, dtype=object), "1", "dNNM output"),
              "parameter": (("parameter",), ds.parameter.values, ds.parameter.attrs),
              "level": variable("level", np.asarray(levels, float), "m", "response level |q_res,z|")}
    return xr.Dataset(data, coords=coords, attrs=ds.attrs)


def _names(levels, outputs=ENVELOPE_OUTPUTS):
    return [f"{o} at {1e3 * lev:g} mm" for o in outputs for lev in levels]


def sobol_study(surrogate, levels, box, settings: dict) -> xr.Dataset:
    """Pick-freeze indices with intervals on ``box`` ((3, 2) kappa ranges); ``settings``: the
    sensitivity section (n_base, estimator, confidence_level, seed)."""
    ds = sobol_indices(level_function(surrogate, levels), box, n_base=settings["n_base"],
                       estimator=settings["estimator"], seed=settings["seed"],
                       confidence_level=settings["confidence_level"], output_names=_names(levels))
    return _by_level(ds, levels)


def pce_cross_check(surrogate, levels, box, settings: dict, mc: xr.Dataset) -> xr.Dataset:
    """``mc`` with the polynomial-chaos indices of the same function (``first_order_pce``,
    ``total_order_pce``) and their largest difference to the pick-freeze ones in the attributes."""
    pce = _by_level(sobol_indices_pce(level_function(surrogate, levels), box, degree=settings["pce_degree"],
                                      n_train=settings["pce_samples"], seed=settings["seed"],
                                      output_names=_names(levels)), levels)
    out = mc.copy()
    for kind in ("first_order", "total_order"):
        out[f"{kind}_pce"] = pce[kind].assign_attrs(
            long_name=f"{pce[kind].attrs['long_name']}, polynomial chaos (degree {settings['pce_degree']})")
        diff = np.abs(out[f"{kind}_pce"] - mc[kind])
        out.attrs[f"{kind}_pce_max_abs_difference"] = float(diff.max())
        inside = (out[f"{kind}_pce"] >= mc[f"{kind}_lower"]) & (out[f"{kind}_pce"] <= mc[f"{kind}_upper"])
        out.attrs[f"{kind}_pce_inside_interval"] = float(inside.mean())
    out.attrs["pce_method"] = pce.attrs["method"]
    out.attrs["pce_basis_size"] = pce.attrs["basis_size"]
    return out


def table(studies: dict) -> pd.DataFrame:
    """Long table (study, output, level_mm, parameter) of every index, interval and PCE value."""
    frames = []
    for study, ds in studies.items():
        names = [v for v in ds.data_vars if v.startswith(("first_order", "total_order"))]
        frame = ds[names].to_dataframe().reset_index()
        frame.insert(0, "study", study)
        frames.append(frame)
    out = pd.concat(frames, ignore_index=True)
    out["level"] = 1e3 * out["level"]
    return out.rename(columns={"level": "level_mm"})
