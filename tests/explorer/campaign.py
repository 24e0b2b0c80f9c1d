"""A small synthetic campaign tree for the explorer's tests: the analytic backbones of
tests/campaign/synthetic.py on 12 training and 4 validation rings, aggregated and fitted by the library
(log transforms as configured), with static.nc contact states and an optimum.yaml.

At the top amplitude 7 of the 12 training rings are "not reached" (status 2, NaN outputs), so fewer
than ``min_training`` remain and no model is fitted there; at the lowest amplitude every ring is stuck
(ζ = 0), so the model of ζ there is constant. The static solve of validation ring FAILED_STATIC
failed (NaN fields, ``n_in_contact`` = -1). The page must say all three instead of drawing NaN.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr
import yaml

from ringdamper.campaign.dataset import aggregate, usable_mask
from ringdamper.campaign.design_space import REFERENCE_RINGS
from ringdamper.campaign.explorer import page_data, write_page
from ringdamper.campaign.kriging import OUTPUTS, fit_campaign
from ringdamper.io import variable, write_netcdf
from tests.campaign.synthetic import KAPPA_STAR, design, dnnm_dataset, write_campaign

ALPHA = np.geomspace(1e-6, 1e-4, 8)
SETTINGS = {"n_starts": 2, "min_training": 6}
N_PAIRS = 12
N_UNREACHED = 7  # training rings not reached at the top amplitude
FAILED_STATIC = "v003"


def static_dataset(kappa, failed: bool = False) -> xr.Dataset:
    """A static state of ``N_PAIRS`` pairs on two axial rows over ±2° of a 0.4 m radius: contact
    pressure growing with κ1 towards the sector centre, gap opening where the pressure is 0; with
    ``failed``, the file of a failed solve (every field NaN, ``n_in_contact`` = -1)."""
    theta = np.tile(np.linspace(-0.035, 0.035, N_PAIRS // 2), 2)
    z = np.repeat([0.032, 0.040], N_PAIRS // 2)
    pressure = np.maximum(2e5 * (1 + 0.5 * kappa[0]) * (1 - (theta / 0.03) ** 2), 0.0)
    gap = np.where(pressure > 0, 0.0, 1e-6 * (np.abs(theta) - 0.03) / 0.005)
    pair = {"pair": variable("pair", np.arange(N_PAIRS), "1", "contact pair")}
    data = {"x": variable("pair", 0.4 * np.cos(theta), "m", "x"), "y": variable("pair", 0.4 * np.sin(theta), "m", "y"),
            "z": variable("pair", z, "m", "z"), "N0": variable("pair", pressure * 1e-5, "N", "normal preload"),
            "pressure": variable("pair", pressure, "Pa", "static contact pressure N0 / area"),
            "gap": variable("pair", gap, "m", "static gap"),
            "kn": variable("pair", np.full(N_PAIRS, 1e8), "N/m", "normal stiffness"),
            "kt": variable("pair", np.full(N_PAIRS, 1e8), "N/m", "tangential stiffness")}
    if failed:
        for name in data:
            data[name] = data[name][0], np.full(N_PAIRS, np.nan), data[name][2]
    return xr.Dataset(data, coords=pair, attrs={"kappa": np.asarray(kappa, float), "status": 99 if failed else 0,
                                                "n_in_contact": -1 if failed else int(np.sum(pressure > 0))})


def build_tree(root: Path) -> dict:
    """Write the tree under ``root``; paths of its dataset.nc, kriging.nc, optimum.yaml and static.nc files."""
    samples = design(12, 4)
    unreached = set(samples[samples.split == "training"].gid.iloc[:N_UNREACHED])
    overrides = {}
    for row in samples.itertuples():
        status = [0] * (ALPHA.size - 1) + [2 if row.gid in unreached else 0]
        ds = dnnm_dataset([row.kappa1, row.kappa2, row.kappa3], ALPHA, status)
        ds["zeta"].values[0] = 0.0  # stuck
        if row.gid in unreached:
            for name in OUTPUTS:
                ds[name].values[-1] = np.nan
        overrides[row.gid] = ds
    dataset = aggregate(samples, write_campaign(root, samples, ALPHA, overrides))
    mask = usable_mask(dataset)
    train = (dataset.split == "training").values
    kriging = fit_campaign(dataset.isel(geometry=train), mask=mask.isel(geometry=train), settings=SETTINGS)
    paths = {"dataset": root / "campaign" / "dataset.nc", "kriging": root / "surrogate" / "kriging.nc",
             "optimum": root / "surrogate" / "optimum.yaml", "static": {}}
    write_netcdf(dataset, paths["dataset"])
    write_netcdf(kriging, paths["kriging"])
    paths["optimum"].write_text(yaml.safe_dump({"kappa": KAPPA_STAR.tolist()}))
    for row in samples.itertuples():
        path = root / "geometry" / row.gid / "static.nc"
        write_netcdf(static_dataset([row.kappa1, row.kappa2, row.kappa3], row.gid == FAILED_STATIC), path)
        paths["static"][row.gid] = path
    return paths


def build_page(paths: dict, out: Path) -> Path:
    """The explorer page of the tree (reference amplitude 5e-5 m, inside the synthetic backbones' range)."""
    data = page_data(paths["dataset"], paths["kriging"], paths["optimum"], paths["static"], REFERENCE_RINGS, 5e-5)
    write_page(data, out)
    return out
