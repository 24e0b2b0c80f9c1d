"""The campaign's surrogates: one Kriging model per (output, modal amplitude) → ``kriging.nc`` (paper §3.2).

Each model is fitted by :func:`.fit.fit_model` on the geometries the training mask allows at that
amplitude; it stores θ, ν, β, σ, the maximised log-likelihood ℓ, the leave-one-out residuals
eᵢ = yᵢ - ŷ₋ᵢ(xᵢ) and the variance factor ψ of :mod:`.gp`, and the predictivity coefficient

    Q² = 1 - Σeᵢ² / Σ(yᵢ - ȳ)²     (eᵢ with fixed hyperparameters, Dubrule 1983).

Each model is fitted to z = T(y), T the output's ``surrogate.transform`` (:mod:`.transform`). Data are
constant (the constant model β = mean(z)) when their spread is below CONSTANT_RTOL times the output's
largest |y| over the campaign (ζ = ±1e-17 of the stuck amplitudes is 0 beside ζ ~ 1e-3); β, σ, ψ
belong to z, the stored training values, leave-one-out residuals and Q² to y (eᵢ = yᵢ - T⁻¹(zᵢ - e_z,ᵢ)).

A model is Gaussian-process (status 0), constant (constant data, status 1) or not fitted (fewer than
``min_training`` usable geometries, status 2). The models are independent fits, each seeded by the
settings alone, so the process pool that runs them side by side does not change them. Layout of
``kriging.nc``: docs/surrogate.md.
"""

from __future__ import annotations

import logging

import numpy as np
import xarray as xr
from threadpoolctl import threadpool_limits

from ...io import variable
from ...workers import worker_pool
from .fit import fit_model, is_constant_data
from .gp import q2
from .settings import check_settings
from .transform import Transform

log = logging.getLogger(__package__)  # one logger for the package: ringdamper.campaign.kriging

OUTPUTS = ("q_res_z", "omega0", "zeta", "gamma")
PARAMETERS = ("kappa1", "kappa2", "kappa3")
STATUS_GP, STATUS_CONSTANT, STATUS_UNFITTED = 0, 1, 2
STATUS_MEANINGS = "gaussian_process constant_data too_few_training_points"


def _training_mask(dataset: xr.Dataset, mask) -> np.ndarray:
    shape = (dataset.sizes["geometry"], dataset.sizes["amplitude"])
    if mask is None:
        return np.ones(shape, dtype=bool)
    if isinstance(mask, xr.DataArray):
        mask = mask.transpose("geometry", *[d for d in ("amplitude",) if d in mask.dims]).values
    mask = np.asarray(mask, dtype=bool)
    if mask.shape == shape[:1]:
        mask = np.repeat(mask[:, None], shape[1], axis=1)
    if mask.shape != shape:
        raise ValueError(f"mask has shape {mask.shape}; expected (geometry,) = {shape[:1]} "
                         f"or (geometry, amplitude) = {shape}")
    return mask


def _check_inputs(dataset: xr.Dataset, outputs) -> np.ndarray:
    if not {"geometry", "amplitude"} <= set(dataset.dims):
        raise ValueError(f"dataset dims are {tuple(dataset.dims)}; expected (geometry, amplitude)")
    missing = [k for k in (*PARAMETERS, *outputs) if k not in dataset.variables]
    if missing:
        raise ValueError(f"dataset lacks {missing}; needs coords {PARAMETERS} and data vars {tuple(outputs)}")
    kappa = np.column_stack([dataset[k].values for k in PARAMETERS]).astype(float)
    if not np.all(np.isfinite(kappa)) or np.abs(kappa).max() > 1.0:
        raise ValueError("dataset kappa1..3 must be finite and within [-1, 1]")
    return kappa


def _physical_residuals(transform: Transform, y: np.ndarray, model) -> np.ndarray:
    """Leave-one-out residuals of y: eᵢ = yᵢ - T⁻¹(zᵢ - e_z,ᵢ) (e_z,ᵢ those of the model of z)."""
    e = model.loo_residuals()
    return e if transform.kind == "identity" else y - transform.inverse(model.y - e)


def _fit_task(task):
    """:func:`fit_model` of one ``(x, y, settings, name, constant)`` (a top-level function: process pools pickle it)."""
    return fit_model(*task)


def _fit_all(tasks: list, workers: int) -> list:
    """:func:`fit_model` of every task, in order, on ``workers`` single-threaded processes (each fit is
    seeded by the settings alone, so the models do not depend on the number of workers). The fits are
    small dense problems: in the calling process too they run on one BLAS thread (more only wait)."""
    if workers <= 1 or len(tasks) < 2:
        with threadpool_limits(1):
            return [_fit_task(t) for t in tasks]
    with worker_pool(workers) as pool:
        return list(pool.map(_fit_task, tasks, chunksize=max(1, len(tasks) // (4 * workers))))


def fit_campaign(dataset: xr.Dataset, outputs=OUTPUTS, mask=None, settings: dict | None = None,
                 workers: int = 1) -> xr.Dataset:
    """One Kriging model per (output, amplitude) on the usable geometries → the ``kriging.nc`` Dataset.

    dataset: dims (geometry, amplitude), coords kappa1..3 (on geometry), data vars ``outputs``.
    mask: bool (geometry,) or (geometry, amplitude), True where a point may train (default all): the
        caller excludes validation geometries and failed solves; a NaN/inf output under the mask is an
        error naming the output and amplitude. Geometries never used are not stored.
    settings: the ``surrogate`` section; keys and defaults in DEFAULT_SETTINGS (see check_settings).
    workers: processes fitting the models side by side (the result does not depend on it).
    Layout of the result: docs/surrogate.md.
    """
    s = check_settings(settings)
    outputs = tuple(outputs)
    dataset, kappa, use, values = _training_inputs(dataset, outputs, mask)
    tasks, keys, transforms = _fit_tasks(dataset, outputs, kappa, use, values, s)
    fitted = {(out, ia): (rows, *fit) for (out, ia, rows), fit in zip(keys, _fit_all(tasks, workers))}
    train = {out: np.where(use, values[out], np.nan).T for out in outputs}
    models = [_output_models(fitted, out, transforms[io], train[out]) for io, out in enumerate(outputs)]
    per_output = {}
    for out, m in zip(outputs, models):
        per_output.update(_output_variables(dataset[out], train[out], m, s))
    data = {**_model_variables(models, transforms, kappa, use, s), **per_output}
    return xr.Dataset(data, coords=_fit_coords(dataset, outputs, kappa), attrs=_fit_attrs(s))


def _fit_tasks(dataset: xr.Dataset, outputs: tuple, kappa: np.ndarray, use: np.ndarray, values: dict, s: dict):
    """The fits to run: one ``(x, z, settings, name, constant)`` task of :func:`fit_model` per (output,
    amplitude) with at least ``min_training`` usable geometries, z = T(y); their keys (output, amplitude
    index, training rows) and the (output, amplitude) array of transforms T (identity where not fitted)."""
    n_amp = dataset.sizes["amplitude"]
    tasks, keys = [], []
    transforms = np.full((len(outputs), n_amp), Transform(), dtype=object)
    scales = {out: float(np.max(np.abs(values[out]), where=use & np.isfinite(values[out]), initial=0.0))
              for out in outputs}  # the output's magnitude over the campaign: round-off is relative to it
    for io, out in enumerate(outputs):
        for ia in range(n_amp):
            rows = np.flatnonzero(use[:, ia])
            amp = float(dataset["amplitude"].values[ia])
            if len(rows) < s["min_training"]:
                log.warning("%s at amplitude %.4g: %d usable geometries < surrogate.min_training = %d; not fitted",
                            out, amp, len(rows), s["min_training"])
                continue
            name = f"{out} at amplitude[{ia}] = {amp:.6g}"
            y = values[out][rows, ia]
            finite = bool(np.all(np.isfinite(y)))  # fit_model names the non-finite values
            kind = s["transform"].get(out, "identity") if finite else "identity"
            transforms[io, ia] = Transform.for_data(kind, y, s["log_offset"], scales[out], name)
            constant = finite and is_constant_data(y, scales[out])
            tasks.append((kappa[rows], transforms[io, ia].forward(y), s, name, constant))
            keys.append((out, ia, rows))
    return tasks, keys, transforms


def _output_models(fitted: dict, out: str, transforms: np.ndarray, train: np.ndarray) -> dict:
    """The models of output ``out`` by amplitude (``train``: its (amplitude, geometry) training values, NaN
    where unused): status, θ, nugget, ℓ, β, σ, ψ, log offset c, the leave-one-out residuals of y and Q²
    (NaN, status unfitted, at an amplitude without a model)."""
    n_amp = train.shape[0]
    m = {key: np.full(n_amp, np.nan) for key in ("nugget", "loglik", "beta", "sigma", "factor", "offset", "q2")}
    m["status"] = np.full(n_amp, STATUS_UNFITTED, dtype=np.int8)
    m["scale"] = np.full((n_amp, len(PARAMETERS)), np.nan)
    m["loo"] = np.full(train.shape, np.nan)
    for ia in range(n_amp):
        if (out, ia) not in fitted:
            continue
        rows, model, ll = fitted[out, ia]
        m["status"][ia] = STATUS_CONSTANT if model.is_constant else STATUS_GP
        m["scale"][ia], m["nugget"][ia], m["loglik"][ia] = model.scale, model.nugget, ll
        m["beta"][ia], m["sigma"][ia], m["factor"][ia] = model.beta, model.sigma, model.loo_variance_factor()
        m["offset"][ia] = transforms[ia].offset
        m["loo"][ia, rows] = _physical_residuals(transforms[ia], train[ia, rows], model)
        m["q2"][ia] = q2(train[ia, rows], m["loo"][ia, rows])
    return m


def _output_variables(y: xr.DataArray, train: np.ndarray, m: dict, s: dict) -> dict:
    """The variables of one output ``y`` on (amplitude[, geometry]): its training values, log offsets, β, σ
    (of z = T(y)), variance factors and leave-one-out residuals (of y), from its models ``m``."""
    out = y.name
    units, long_name = y.attrs.get("units", "1"), y.attrs.get("long_name", out)
    latent = Transform(s["transform"].get(out, "identity"))
    z_units, z_name = latent.units(units), latent.describe(out, units)
    return {
        out: variable(("amplitude", "geometry"), train, units, f"training values of {long_name} (NaN: not used)"),
        f"{out}_offset": variable("amplitude", m["offset"], units,
                                  f"offset c of the log transform of {out} (0: identity)"),
        f"{out}_beta": variable("amplitude", m["beta"], z_units, f"Kriging constant trend of {z_name}"),
        f"{out}_sigma": variable("amplitude", m["sigma"], z_units, f"Kriging process standard deviation of {z_name}"),
        f"{out}_variance_factor": variable(
            "amplitude", m["factor"], "1", f"leave-one-out calibration factor of the predictive variance of {out}"),
        f"{out}_loo_residual": variable(("amplitude", "geometry"), m["loo"], units,
                                        f"leave-one-out residual of {out} (fixed hyperparameters)"),
    }


def _model_variables(models: list, transforms: np.ndarray, kappa: np.ndarray, use: np.ndarray, s: dict) -> dict:
    """The variables of the training geometries and of the models on (output, amplitude), ``models`` those
    of :func:`_output_models` in the order of the outputs."""
    n_out, n_amp = transforms.shape

    def stacked(key):
        return np.stack([m[key] for m in models])

    return {
        "kappa": variable(("geometry", "parameter"), kappa, "1",
                          "normalised shape parameters of the training geometries"),
        "training_mask": variable(("amplitude", "geometry"), use.T.astype(np.int8), "1",
                                  "1 where the geometry trains the models of that amplitude"),
        "kernel": variable(("output", "amplitude"), np.full((n_out, n_amp), s["kernel"], dtype=object), "1",
                           "correlation function of the model"),
        "transform": variable(("output", "amplitude"), np.vectorize(lambda t: t.kind, otypes=[object])(transforms),
                              "1", "output transform of the model (identity, log)"),
        "scale": variable(("output", "amplitude", "parameter"), stacked("scale"), "1",
                          "correlation length theta per parameter"),
        "nugget": variable(("output", "amplitude"), stacked("nugget"), "1", "nugget factor (fraction of sigma^2)"),
        "status": variable(("output", "amplitude"), stacked("status"), "1", "model status", flag_values=[0, 1, 2],
                           flag_meanings=STATUS_MEANINGS),
        "n_training": variable(("output", "amplitude"), np.tile(use.sum(axis=0), (n_out, 1)), "1",
                               "number of training points of the model"),
        "log_likelihood": variable(("output", "amplitude"), stacked("loglik"), "1",
                                   "maximised reduced log-likelihood"),
        "q2": variable(("output", "amplitude"), stacked("q2"), "1", "leave-one-out predictivity coefficient Q2"),
    }


def _fit_coords(dataset: xr.Dataset, outputs: tuple, kappa: np.ndarray) -> dict:
    amp_attrs = {"units": "1", "long_name": "modal amplitude", **dataset["amplitude"].attrs}
    return {
        "output": variable("output", np.array(outputs, dtype=object), "1", "Kriging output"),
        "amplitude": ("amplitude", dataset["amplitude"].values, amp_attrs),
        "parameter": variable("parameter", np.array(PARAMETERS, dtype=object), "1", "shape parameter"),
        "geometry": variable("geometry", _geometry_ids(dataset, kappa), "1", "training geometry"),
    }


def fitted_on(fit: xr.Dataset, dataset: xr.Dataset, outputs=OUTPUTS, mask=None, settings: dict | None = None,
              kappa_tolerance: float = 0.0) -> bool:
    """True when ``fit`` (a ``kriging.nc`` Dataset) is what :func:`fit_campaign` returns for these arguments:
    fitted by this OpenTURNS with the same settings on the same geometries, amplitudes, training mask and
    training values, bit for bit, and κ within ``kappa_tolerance``. The fit is a deterministic function of
    those (seeded starts; the worker count does not matter), so such a ``fit`` need not be fitted again:
    the adaptive design's stopping round has fitted exactly the campaign's training rings (docs/adaptive.md,
    *In Snakemake*)."""
    outputs = tuple(outputs)
    dataset, kappa, use, values = _training_inputs(dataset, outputs, mask)
    attrs = _fit_attrs(check_settings(settings))
    if list(fit["output"].values) != list(outputs) or fit.sizes.get("geometry") != len(kappa):
        return False
    if not np.max(np.abs(fit["kappa"].values - kappa), initial=0.0) <= kappa_tolerance:
        return False
    arrays = [(fit["geometry"].values, _geometry_ids(dataset, kappa)),
              (fit["amplitude"].values, dataset["amplitude"].values),
              (fit["training_mask"].values, use.T.astype(np.int8)),
              *((fit[out].values, np.where(use, values[out], np.nan).T) for out in outputs)]
    same_data = all(a.shape == b.shape and np.array_equal(a, b, equal_nan=a.dtype.kind == "f") for a, b in arrays)
    return same_data and all(np.array_equal(np.atleast_1d(fit.attrs.get(k)), np.atleast_1d(v))
                             for k, v in attrs.items())


def _training_inputs(dataset: xr.Dataset, outputs: tuple, mask):
    """The geometries that train at least one model (the only ones a fit stores), their κ, training mask
    (geometry, amplitude) and output values."""
    kappa = _check_inputs(dataset, outputs)
    use = _training_mask(dataset, mask)
    used = use.any(axis=1)
    dataset, kappa, use = dataset.isel(geometry=used), kappa[used], use[used]
    values = {out: dataset[out].transpose("geometry", "amplitude").values.astype(float) for out in outputs}
    return dataset, kappa, use, values


def _geometry_ids(dataset: xr.Dataset, kappa: np.ndarray) -> np.ndarray:
    return dataset["geometry"].values if "geometry" in dataset.coords else np.arange(len(kappa))


def _fit_attrs(s: dict) -> dict:
    """The attributes of a fit: the OpenTURNS version and the settings."""
    import openturns as ot

    return {"openturns_version": ot.__version__, "kernel": s["kernel"], "n_starts": s["n_starts"],
            "seed": s["seed"], "scale_bounds": list(s["scale_bounds"]), "scale_bounds_unit": "kappa-domain width (2)",
            "nugget_setting": list(np.atleast_1d(s["nugget"])), "min_training": s["min_training"],
            "transform": ", ".join(f"{k}: {v}" for k, v in s["transform"].items()), "log_offset": s["log_offset"]}
