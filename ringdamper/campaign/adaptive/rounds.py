"""One round of the adaptive loop, and the whole loop on any evaluation function.

A round k (k = 1, 2, ...) reads the dnnm.nc of every training ring computed so far (the initial design
and the rings of rounds 1 .. k-1), fits the surrogates (:func:`.model.fit_surrogate`), finds their
predicted optimum (best candidate of the round's set, polished by
:func:`~ringdamper.campaign.exploration.polish`), decides whether to stop (:mod:`.stopping`) and, if
not, picks the next batch (:mod:`.acquisition`, :mod:`.batch`). A ring whose chain failed (no usable
point) is excluded from the fit and named in the record; a round whose new rings all failed raises
:class:`RoundFailedError` naming them. The record of a round (a dict, written as YAML by the rule) holds
the chosen rings with their acquisition values, the estimates of the validation error
(:mod:`.accuracy`), the optimum and the stop decision.
"""
from __future__ import annotations

import logging

import numpy as np
import pandas as pd
import xarray as xr

from ..dataset import aggregate, kappa, usable_mask
from ..exploration import backbones, polish, predicted_zeta_max
from ..sampling import make_samples
from .accuracy import RULE_ESTIMATE, domain_points, estimates
from .acquisition import acquisition
from .batch import select_batch
from .design import candidates, round_gid, with_rounds
from .model import RoundModels, fit_surrogate, training_spread
from .stopping import decide

log = logging.getLogger(__name__)

POLISH_STEP = 0.1  # start simplex of the optimum's polish (normalised kappa)


class RoundFailedError(RuntimeError):
    """Every ring a round added failed: the loop cannot learn from it."""


def _floats(values) -> list:
    return [float(v) for v in np.asarray(values, float).ravel()]


def training_dataset(samples: pd.DataFrame, records: list[dict], paths: dict) -> tuple[xr.Dataset, xr.DataArray]:
    """The dataset of the training rings computed before the next round (the initial design's and those
    ``records`` chose; ``paths`` gid -> dnnm.nc) and its usable mask. A ring with no usable point is
    excluded (logged); if every ring of the last round is, :class:`RoundFailedError` names them."""
    table = with_rounds(samples, records)
    table = table[table.split == "training"].reset_index(drop=True)
    ds = aggregate(table, paths)
    mask = usable_mask(ds, logger=log)
    failed = [str(g) for g in ds.geometry.values[~mask.values.any(axis=1)]]
    if failed:
        log.warning("excluded from the fit (no usable point): %s", failed)
    if records:
        last = [c["gid"] for c in records[-1]["chosen"]]
        if last and set(last) <= set(failed):
            reasons = "; ".join(f"{g} ({ds.reason.sel(geometry=g).item()})" for g in last)
            raise RoundFailedError(f"every ring of round {records[-1]['round']} failed: {reasons}")
    return ds, mask


def predicted_optimum(surrogate, points: np.ndarray, q_max: float) -> dict:
    """The best of ``points`` for the optimum criterion, polished: kappa, zeta_max and its std."""
    zmax = predicted_zeta_max(backbones(surrogate, points, ("q_res_z", "zeta"), with_std=False), q_max)[0]

    def neg_zeta_max(k):
        return -predicted_zeta_max(backbones(surrogate, k[None], ("q_res_z", "zeta"), with_std=False), q_max)[0][0]

    k_opt, _ = polish(neg_zeta_max, points[int(np.nanargmax(zmax))], POLISH_STEP)
    bb = backbones(surrogate, k_opt[None], ("q_res_z", "zeta"))
    mu, j = predicted_zeta_max(bb, q_max)
    return {"kappa": _floats(k_opt), "zeta_max": float(mu[0]), "zeta_max_std": float(bb.std["zeta"][j[0], 0])}


def round_models(dataset: xr.Dataset, mask: xr.DataArray, config: dict, workers: int = 1) -> RoundModels:
    """The models a round reads: fitted on the rings of ``dataset`` with a usable point (``mask``)."""
    usable = mask.values.any(axis=1)
    return fit_surrogate(dataset.isel(geometry=usable), mask.isel(geometry=usable), config["surrogate"], workers)


def plan_round(dataset: xr.Dataset, mask: xr.DataArray, history: list[dict], config: dict, round_: int,
               validation: np.ndarray, workers: int = 1, models: RoundModels | None = None) -> dict:
    """The record of round ``round_`` (module docstring). ``dataset``/``mask``: the training rings so far
    (:func:`training_dataset`); ``history``: the records of the earlier rounds; ``config``: the sampling,
    surrogate and exploration sections; ``validation``: (n, 3) the validation rings, kept away from;
    ``models``: those :func:`round_models` fitted on ``dataset`` (fitted here when not given)."""
    adaptive, q_max = config["sampling"]["adaptive"], config["exploration"]["optimum_max_level"]
    usable = mask.values.any(axis=1)
    models = round_models(dataset, mask, config, workers) if models is None else models
    errors = estimates(models, domain_points(config["sampling"]["seed"]))
    points = candidates(config["sampling"], round_, validation)
    optimum = predicted_optimum(models.surrogate, points, q_max)
    n_computed = dataset.sizes["geometry"]
    decision = decide(errors[RULE_ESTIMATE], [r["optimum"] for r in history] + [optimum], n_computed, adaptive)
    record = {"round": round_, "n_computed": n_computed, "n_usable": int(usable.sum()),
              "excluded": [str(g) for g in dataset.geometry.values[~usable]],
              "estimates": errors, "optimum": optimum, **decision, "chosen": []}
    if decision["stop"]:
        log.info("round %d: stop (%s) after %d training rings", round_, decision["reason"], n_computed)
        return record
    bb = backbones(models.surrogate, points)
    acq = acquisition(bb, training_spread(models.kriging), q_max, optimum["zeta_max"], adaptive["exploit_weight"])
    b = min(adaptive["batch"], adaptive["n_max"] - n_computed)
    picked = select_batch(points, acq["score"], kappa(dataset), b, adaptive["batch_spacing"])
    record["chosen"] = [{"gid": round_gid(round_, i), "kappa": _floats(points[p]), "score": float(acq["score"][p]),
                         "explore": float(acq["explore"][p]), "exploit": float(acq["exploit"][p])}
                        for i, p in enumerate(picked)]
    log.info("round %d: %d training rings, worst error / tolerance %.3g, optimum %s zeta_max %.4g; chose %s",
             round_, n_computed, decision["worst_ratio"], optimum["kappa"], optimum["zeta_max"],
             [c["gid"] for c in record["chosen"]])
    return record


def run_loop(evaluate, config: dict, workers: int = 1) -> tuple[pd.DataFrame, list[dict]]:
    """The whole loop: ``evaluate(table)`` computes the rings of a sample table and returns gid ->
    dnnm.nc path. Returns the final sample table and the round records."""
    samples = make_samples(config["sampling"])
    validation = kappa(samples[samples.split == "validation"])
    paths = dict(evaluate(samples[samples.split == "training"]))
    records: list[dict] = []
    while not (records and records[-1]["stop"]):
        ds, mask = training_dataset(samples, records, paths)
        records.append(plan_round(ds, mask, records, config, len(records) + 1, validation, workers))
        new = with_rounds(samples.iloc[:0], records[-1:])
        if len(new):
            paths.update(evaluate(new))
    return with_rounds(samples, records), records
