"""Reduction stage of one geometry (paper §2.5.1, docs/reduction.md): kappa -> the reduced.nc dataset.

The model is rebuilt from kappa (the mesh is a pure function of kappa and the configuration), reduced
with the ``reduction`` section's mode counts for harmonics 0..H, and stored as its complete modal
basis per harmonic (:func:`~ringdamper.reduction.reduced.reduced_dataset`).
"""
from __future__ import annotations

import logging
import time

import xarray as xr

from ringdamper.fem.model import build_model
from ringdamper.geometry.sector import build_sector
from ringdamper.reduction.reduced import modal_basis, reduce_sector, reduced_dataset

log = logging.getLogger(__name__)


def reduction_sizes(config: dict) -> dict:
    """``n_fi``, ``n_if`` keyword arguments of :func:`reduce_sector` from the configuration."""
    red = config["reduction"]
    return {"n_fi": red["n_fixed_interface_modes"], "n_if": red["n_interface_modes"]}


def run_reduced(config: dict, kappa) -> xr.Dataset:
    """reduced.nc of geometry ``kappa``: harmonics 0..``reduction.n_harmonics``."""
    t0 = time.perf_counter()
    model = build_model(build_sector(config, kappa), config)
    rs = reduce_sector(model, config["operation"]["engine_order"],
                       n_harmonics=config["reduction"]["n_harmonics"], **reduction_sizes(config))
    bases = [modal_basis(rh, rs.B, rs.response_index) for rh in rs.harmonics]
    ds = reduced_dataset(rs, kappa, bases,
                         attrs={"stiffness": "linear elastic at rest (no prestress)",
                                "wall_time_s": time.perf_counter() - t0})
    log.info("kappa=%s %s harmonics=0..%d dofs %s, %s", list(kappa), reduction_sizes(config),
             config["reduction"]["n_harmonics"], rs.dof_counts,
             ", ".join(f"{k} {v:.2f} s" for k, v in rs.timings.items()))
    return ds
