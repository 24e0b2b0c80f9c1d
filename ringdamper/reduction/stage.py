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
from ringdamper.reduction.substructured import morph_model, reduce_on_superelement
from ringdamper.reduction.superelement import load

log = logging.getLogger(__name__)


def reduction_sizes(config: dict) -> dict:
    """``n_fi``, ``n_if`` keyword arguments of :func:`reduce_sector` from the configuration."""
    red = config["reduction"]
    return {"n_fi": red["n_fixed_interface_modes"], "n_if": red["n_interface_modes"]}


def _reduced_sector(config: dict, kappa, superelement):
    """The reduced sector of ring ``kappa``: monolithic, or on the super-element file."""
    counts = reduction_sizes(config)
    eo = config["operation"]["engine_order"]
    if superelement is None:
        model = build_model(build_sector(config, kappa), config)
        return reduce_sector(model, eo, n_harmonics=config["reduction"]["n_harmonics"], **counts)
    se = load(superelement)
    model, split = morph_model(config, kappa, se, superelement)
    return reduce_on_superelement(model, split, se, eo, **counts)


def run_reduced(config: dict, kappa, superelement=None) -> xr.Dataset:
    """reduced.nc of geometry ``kappa``: harmonics 0..``reduction.n_harmonics``; with
    ``superelement`` (a file of ``reduction.superelement``) on the fixed substructure."""
    t0 = time.perf_counter()
    rs = _reduced_sector(config, kappa, superelement)
    bases = [modal_basis(rh, rs.response_index) for rh in rs.harmonics]
    stiffness = "linear elastic at rest (no prestress)"
    ds = reduced_dataset(rs, kappa, bases,
                         attrs={"stiffness": stiffness, "wall_time_s": time.perf_counter() - t0,
                                "substructure": "fixed part super-element" if superelement else "none"})
    log.info("kappa=%s %s harmonics=0..%d dofs %s", list(kappa), reduction_sizes(config),
             config["reduction"]["n_harmonics"], rs.dof_counts)
    return ds
