"""Campaign dataset: every geometry's ``dnnm.nc`` on one ``geometry x amplitude`` table.

``aggregate`` stacks the scalar outputs of the dNNM + E-EBM stage of every geometry of
``samples.csv`` (they share the modal-amplitude grid alpha of ``config.yaml``). A point is *usable*
when its status is 0 (converged) or 3 (converged, the ring's mean rigid-body equilibrium held by the
gauge: flagged by ``held``, kept) and its outputs are finite; every other status (no convergence,
not reached, budget, failed chain) stays in the dataset but is excluded downstream by
:func:`usable_mask`, which logs one warning per geometry naming it and its reason.
:func:`check_training` stops a fit with too few usable training geometries.
"""
from __future__ import annotations

import logging

import netCDF4
import numpy as np
import pandas as pd
import xarray as xr

from ..io import unreadable, variable
from ..status import CHAIN_FAILED, USABLE_STATUS, Status

log = logging.getLogger(__name__)

HELD_STATUS = int(Status.DRIFT)
STATUS_NAMES = {int(s): s.name.lower().replace("_", " ") for s in Status} | {CHAIN_FAILED: "chain failed"}

# dnnm.nc scalars kept in the dataset (optional ones are NaN where a file lacks them)
SCALARS = ("omega0", "frequency", "zeta", "gamma", "phi", "q_res_z", "q_res_z_h1", "rigid_body_imbalance",
           "highest_harmonic_energy", "normal_force_ratio_min", "lifting_pairs", "n_harmonics",
           "jacobian_condition", "ill_conditioned", "truncation_flag", "truncation_error")
OPTIONAL = ("rigid_body_imbalance", "q_res_z_h1", "highest_harmonic_energy", "normal_force_ratio_min",
            "lifting_pairs", "n_harmonics", "jacobian_condition", "ill_conditioned", "truncation_flag",
            "truncation_error")
# the outputs the surrogates model and that must be finite at a usable point
SURROGATE_OUTPUTS = ("q_res_z", "omega0", "zeta", "gamma")


class TrainingSetError(ValueError):
    """Too few usable training geometries for the surrogates."""


def _read_dnnm(path) -> dict:
    """Arrays, units/long_names and attrs of one dnnm.nc (netCDF4 directly: ~10x faster than xarray)."""
    try:
        nc = netCDF4.Dataset(path)
    except FileNotFoundError:
        raise
    except OSError as err:
        raise unreadable(path, err) from err
    with nc:
        nc.set_auto_mask(False)
        out = {"amplitude": nc["amplitude"][:], "status": nc["status"][:].astype(np.int16),
               "reason": str(getattr(nc, "reason", "")), "attrs": {}}
        for name in SCALARS:
            if name in nc.variables:
                out[name] = nc[name][:].astype(float)
                out["attrs"][name] = (nc[name].units, nc[name].long_name)
        out["attrs"]["amplitude"] = (nc["amplitude"].units, nc["amplitude"].long_name)
    return out


def status_summary(status: np.ndarray) -> str:
    """'25 converged, 5 not reached' for one geometry's per-amplitude status."""
    codes, counts = np.unique(status, return_counts=True)
    return ", ".join(f"{n} {STATUS_NAMES.get(int(c), f'status {c}')}" for c, n in zip(codes, counts))


def aggregate(samples: pd.DataFrame, paths: dict) -> xr.Dataset:
    """Dataset ``geometry x amplitude`` of the dnnm.nc files ``paths`` (gid -> path) of every row of
    ``samples`` (columns gid, kappa1..3, split). Raises if a geometry lacks a file or the files'
    amplitude grids differ."""
    missing = [g for g in samples.gid if g not in paths]
    if missing:
        raise ValueError(f"no dnnm.nc given for geometries {missing}")
    files = {gid: _read_dnnm(paths[gid]) for gid in samples.gid}
    first = files[samples.gid.iloc[0]]
    alpha = first["amplitude"]
    for gid, f in files.items():
        if f["amplitude"].shape != alpha.shape or not np.allclose(f["amplitude"], alpha, rtol=1e-12):
            raise ValueError(f"{paths[gid]}: its amplitude grid differs from that of "
                             f"{paths[samples.gid.iloc[0]]}; rerun the dnnm stage with one config")
    meta = {}
    for f in files.values():
        meta = f["attrs"] | meta
    n_g, n_a = len(samples), alpha.size
    data = {}
    for name in SCALARS:
        if name not in meta:
            continue
        arr = np.full((n_g, n_a), np.nan)
        for i, gid in enumerate(samples.gid):
            if name in files[gid]:
                arr[i] = files[gid][name]
        units, long_name = meta[name]
        data[name] = variable(("geometry", "amplitude"), arr, units, long_name)
    status = np.stack([files[g]["status"] for g in samples.gid])
    data["status"] = variable(("geometry", "amplitude"), status, "1",
                              "dNNM point status: " + "; ".join(f"{c} {n}" for c, n in STATUS_NAMES.items()))
    data["held"] = variable(("geometry", "amplitude"), (status == HELD_STATUS).astype(np.int8), "1",
                            "1 where the ring's mean rigid-body equilibrium is held by the gauge (status 3)")
    reasons = [files[g]["reason"] or status_summary(files[g]["status"]) for g in samples.gid]
    data["reason"] = variable("geometry", np.array(reasons, dtype=object), "1",
                              "failure reason of the geometry's chain, else its status counts")
    coords = {
        "geometry": variable("geometry", samples.gid.to_numpy(dtype=object), "1", "geometry id (gid)"),
        "amplitude": variable("amplitude", alpha, *meta["amplitude"]),
        "split": variable("geometry", samples.split.to_numpy(dtype=object), "1",
                          "design split: training, validation or reference"),
    }
    for i in (1, 2, 3):
        coords[f"kappa{i}"] = variable("geometry", samples[f"kappa{i}"].to_numpy(float), "1",
                                       f"normalised shape parameter kappa{i}")
    return xr.Dataset(data, coords=coords, attrs={"usable_status": list(USABLE_STATUS)})


def flagged_truncations(ds: xr.Dataset) -> list[str]:
    """One line per geometry with points whose harmonic raise stopped (``truncation_flag`` 1 over its LU
    budget, 2 failed; docs/nonlinear_core.md §4.5): its gid and split, the count of each, their
    amplitudes and the largest estimated truncation error. [] where no point is flagged or the dataset
    has no flags (files from before the flag)."""
    if "truncation_flag" not in ds:
        return []
    flag, error, alpha = ds.truncation_flag.values, ds.truncation_error.values, ds.amplitude.values
    lines = []
    for i in np.flatnonzero(np.nan_to_num(flag).any(axis=1)):
        hit = np.flatnonzero(np.nan_to_num(flag[i]) > 0)
        over, failed = int(np.sum(flag[i] == 1)), int(np.sum(flag[i] == 2))
        lines.append(f"{ds.geometry.values[i]} ({ds.split.values[i]}): {hit.size} point(s) keep a lower "
                     f"harmonic truncation ({over} raise(s) over budget, {failed} failed) at alpha = "
                     + ", ".join(f"{a:.3g}" for a in alpha[hit])
                     + f"; estimated truncation error up to {np.nanmax(error[i, hit]):.2g}")
    return lines


def kappa(ds: xr.Dataset) -> np.ndarray:
    """(geometry, 3) array of the shape parameters."""
    return np.column_stack([ds[f"kappa{i}"].values for i in (1, 2, 3)])


def usable_mask(ds: xr.Dataset, outputs=SURROGATE_OUTPUTS, logger: logging.Logger = log) -> xr.DataArray:
    """Boolean ``geometry x amplitude`` mask of the points the surrogates may use: status 0 or 3 and
    every one of ``outputs`` finite. One warning per geometry with an excluded point, naming it,
    its split, how many amplitudes are excluded and its reason."""
    ok = ds.status.isin(list(USABLE_STATUS))
    for name in outputs:
        ok = ok & np.isfinite(ds[name])
    for i in np.flatnonzero(~ok.values.all(axis=1)):
        g = ds.isel(geometry=i)
        n_bad = int((~ok.values[i]).sum())
        logger.warning("geometry %s (%s) excluded at %d of %d amplitudes: %s", g.geometry.item(),
                       g.split.item(), n_bad, ds.sizes["amplitude"], g.reason.item())
    return ok.rename("usable")


def check_training(ds: xr.Dataset, mask: xr.DataArray, minimum: int) -> None:
    """Raise :class:`TrainingSetError` if, at any amplitude, fewer than ``minimum`` training
    geometries are usable; the message names the amplitudes and the unusable training geometries."""
    train = (ds.split == "training").values
    counts = mask.values[train].sum(axis=0)
    short = np.flatnonzero(counts < minimum)
    if short.size == 0:
        return
    gids = ds.geometry.values[train]
    bad = sorted({g for j in short for g in gids[~mask.values[train, j]]})
    reasons = {g: ds.reason.sel(geometry=g).item() for g in bad}
    alpha = ds.amplitude.values
    raise TrainingSetError(
        f"only {counts[short].min()} usable training geometries at {short.size} amplitude(s) "
        f"(alpha = {alpha[short[0]]:.3g} ... {alpha[short[-1]]:.3g}), below surrogate.min_training = "
        f"{minimum}; unusable there: " + "; ".join(f"{g} ({r})" for g, r in reasons.items()))
