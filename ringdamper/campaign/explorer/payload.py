"""The data of the design explorer page: the Kriging models' parameters, the computed rings and the presets.

Every model of ``kriging.nc`` is exported as the parameters :class:`~ringdamper.campaign.kriging.KrigingSurrogate`
rebuilds it from: kernel, correlation lengths θ, nugget ν, trend β, amplitude σ, variance factor ψ, the
output transform (kind and offset c), and its training set (the rows of the training κ it uses and
the transformed training values z = T(y)). The page factorises R itself and evaluates the predictor
and variance of :mod:`ringdamper.campaign.kriging.gp`; no prediction is precomputed. A model that was
not fitted is ``null``; a constant model has σ = 0.

The computed rings are the training and validation geometries of the dataset: κ, the usable points
of their backbones (``null`` elsewhere) and the contact maps of their static.nc (N0 / area in Pa and
the gap in m per contact pair, at the pair's circumferential arc position and axial position in m).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import xarray as xr
import yaml

from ...io import InputFileError, read_netcdf
from ...static.surface import surface_coords
from ...status import USABLE_STATUS
from ..kriging import OUTPUTS, KrigingSurrogate

#: What each input file must hold for the page (variables), named in the error of a foreign file.
REQUIRED = {
    "kriging.nc": ("output", "amplitude", "kappa", "training_mask", "kernel", "scale", "nugget", "status",
                   *OUTPUTS, *(f"{o}_{k}" for o in OUTPUTS for k in ("beta", "sigma", "variance_factor"))),
    "dataset.nc": ("amplitude", "split", "kappa1", "kappa2", "kappa3", "status", *OUTPUTS),
    "static.nc": ("x", "y", "z", "pressure", "gap"),
}
RING_SPLITS = ("training", "validation")  # the computed rings the page offers as nearest neighbours


def read_input(path, kind: str) -> xr.Dataset:
    """The NetCDF ``path`` of ``kind`` (a key of :data:`REQUIRED`); :class:`InputFileError` naming the
    file when it is missing, unreadable or lacks a variable of that kind."""
    if not Path(path).is_file():
        raise InputFileError(f"{path}: missing (the explorer needs this {kind})")
    ds = read_netcdf(path)
    missing = [v for v in REQUIRED[kind] if v not in ds.variables]
    if missing:
        raise InputFileError(f"{path}: not a ringdamper {kind}: {missing[0]} missing")
    return ds


def finite_list(values) -> list:
    """``values`` as a (nested) list of floats, NaN and ±inf as None (JSON null)."""
    arr = np.asarray(values, dtype=float)
    return [finite(v) for v in arr.ravel()] if arr.ndim == 1 else [finite_list(row) for row in arr]


def finite(value: float) -> float | None:
    """``value``, or None (JSON null) when it is NaN or ±inf."""
    return float(value) if math.isfinite(value) else None


def model_parameters(surrogate: KrigingSurrogate, kriging: xr.Dataset) -> dict:
    """output -> list over the amplitudes of each model's parameters (module doc), None if not fitted."""
    kappa = kriging["kappa"].transpose("geometry", "parameter").values
    rows_of = {kappa[rows].tobytes(): np.flatnonzero(rows)
               for rows in kriging["training_mask"].transpose("amplitude", "geometry").values.astype(bool)}
    models = {out: [None] * kriging.sizes["amplitude"] for out in surrogate.outputs}
    for group in surrogate.groups.values():
        for out, ia, model in group:
            transform = surrogate.transform(out, ia)
            models[out][ia] = {  # a constant model (σ = 0) has no θ nor ν: null
                "kernel": model.kernel, "scale": finite_list(model.scale), "nugget": finite(model.nugget),
                "beta": model.beta, "sigma": model.sigma, "variance_factor": finite(model.variance_factor),
                "transform": transform.kind, "offset": transform.offset,
                "rows": rows_of[model.x.tobytes()].tolist(), "z": model.y.tolist()}
    return models


def contact_map(static: xr.Dataset) -> dict:
    """Per-pair arc position s and axial position z (m), N0 / area (Pa) and gap (m) of one static state."""
    s, z = surface_coords(static)
    return {"s": finite_list(s), "z": finite_list(z), "pressure": finite_list(static["pressure"].values),
            "gap": finite_list(static["gap"].values),
            "n_in_contact": int(static.attrs.get("n_in_contact", int(np.sum(static["pressure"].values > 0))))}


def computed_rings(dataset: xr.Dataset, statics: dict) -> list:
    """The training and validation rings: gid, split, κ, the usable points of the four outputs (None
    elsewhere) and the contact maps (gid -> static.nc path in ``statics``; None when not given)."""
    usable = dataset["status"].isin(list(USABLE_STATUS)).transpose("geometry", "amplitude").values
    rings = []
    for i, gid in enumerate(dataset["geometry"].values):
        split = str(dataset["split"].values[i])
        if split not in RING_SPLITS:
            continue
        backbone = {out: finite_list(np.where(usable[i], dataset[out].transpose("geometry", "amplitude").values[i],
                                              np.nan)) for out in OUTPUTS}
        path = statics.get(str(gid))
        rings.append({"gid": str(gid), "split": split,
                      "kappa": [float(dataset[f"kappa{k}"].values[i]) for k in (1, 2, 3)],
                      "backbone": backbone,
                      "contact": contact_map(read_input(path, "static.nc")) if path else None})
    return rings


def presets(optimum_yaml, reference_rings: dict) -> dict:
    """label -> κ: the reference rings (the default first) and the optimum of optimum.yaml."""
    with open(optimum_yaml) as fh:
        record = yaml.safe_load(fh)
    if not isinstance(record, dict) or "kappa" not in record or len(record["kappa"]) != 3:
        raise InputFileError(f"{optimum_yaml}: not a ringdamper optimum.yaml: kappa (3 values) missing")
    return {"default": list(reference_rings["default"]), "optimum": [float(k) for k in record["kappa"]],
            **{label: list(k) for label, k in reference_rings.items() if label != "default"}}


def page_data(dataset_path, kriging_path, optimum_yaml, statics: dict, reference_rings: dict,
              reference_amplitude: float) -> dict:
    """Everything the page shows (module doc), JSON-ready. ``statics``: gid -> static.nc path;
    ``reference_amplitude`` (m): the |q_res,z| the default ring's predicted backbone reaches at the
    initial forcing of the forcing view."""
    dataset = read_input(dataset_path, "dataset.nc")
    kriging = read_input(kriging_path, "kriging.nc")
    surrogate = KrigingSurrogate(kriging)
    if not np.allclose(kriging["amplitude"].values, dataset["amplitude"].values, rtol=1e-12):
        raise InputFileError(f"{kriging_path}: its amplitude grid differs from that of {dataset_path}")
    outputs = {out: {"units": dataset[out].attrs.get("units", "1"),
                     "long_name": dataset[out].attrs.get("long_name", out)} for out in OUTPUTS}
    return {
        "amplitude": finite_list(kriging["amplitude"].values),
        "amplitude_units": kriging["amplitude"].attrs.get("units", "1"),
        "outputs": outputs,
        "training_kappa": finite_list(kriging["kappa"].transpose("geometry", "parameter").values),
        "models": model_parameters(surrogate, kriging),
        "rings": computed_rings(dataset, statics),
        "presets": presets(optimum_yaml, reference_rings),
        "reference_amplitude": float(reference_amplitude),
    }
