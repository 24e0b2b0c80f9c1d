"""Kriging training-set size: validation error on the held-out geometries for plain LHS designs and
for sequential designs of the same size, all drawn from the campaign's training pool.

Pool-based designs (no new chain runs): the pool is the campaign's training geometries (27 factorial
+ 73 LHS points). A *plain LHS* design of size n is a seeded Latin hypercube of n points in
[-1, 1]^3, each replaced by its nearest unused pool geometry. A *sequential* design starts from the
LHS design of the smallest size and adds one pool geometry at a time where a Kriging model of the
per-geometry zeta_max (refitted after every addition) has the largest predictive variance
(``variance``) or the largest expected improvement of the maximum, EI = (mu - f*) Phi(u) + s phi(u),
u = (mu - f*)/s, f* the best zeta_max so far (``ei``; Jones, Schonlau & Welch 1998). Every design is
then fitted as the campaign fits (one model per output and amplitude, ``campaign.kriging``) and its
predicted backbones are read like computed ones (``quantities.user_quantities``) at the validation
geometries: the error of a quantity is the RMS over those geometries of its relative error.
"""

from __future__ import annotations

import time

import numpy as np
import xarray as xr
from scipy.stats import norm, qmc

from ringdamper.campaign.dataset import kappa as kappa_of
from ringdamper.campaign.dataset import usable_mask
from ringdamper.campaign.exploration import backbones
from ringdamper.campaign.kriging import KrigingSurrogate, fit_campaign, fit_model

from .quantities import user_quantities

DESIGNS = ("lhs", "variance", "ei")


def backbone_dataset(amplitude, q, zeta, freq, gamma, status=None) -> xr.Dataset:
    """A minimal backbone (the variables ``user_quantities`` reads) from arrays over amplitude."""
    status = np.zeros(len(amplitude), int) if status is None else status
    return xr.Dataset({"q_res_z": ("amplitude", q), "zeta": ("amplitude", zeta), "frequency": ("amplitude", freq),
                       "gamma": ("amplitude", gamma), "status": ("amplitude", status)},
                      coords={"amplitude": amplitude})


def computed_quantities(dataset: xr.Dataset, gid: str, levels, gammas, max_level) -> dict:
    """User quantities of geometry ``gid`` of the campaign dataset (frequency read as omega0)."""
    g = dataset.sel(geometry=gid)
    return user_quantities(backbone_dataset(dataset.amplitude.values, g.q_res_z.values, g.zeta.values,
                                            g.omega0.values, g.gamma.values, g.status.values), levels, gammas,
                           max_level)


def lhs_design(pool_kappa: np.ndarray, n: int, seed: int) -> list[int]:
    """Indices of the pool geometries nearest to a seeded n-point LHS of [-1, 1]^3 (each used once)."""
    points = 2.0 * qmc.LatinHypercube(d=pool_kappa.shape[1], seed=seed).random(n) - 1.0
    chosen: list[int] = []
    for p in points:
        d = np.linalg.norm(pool_kappa - p, axis=1)
        d[chosen] = np.inf
        chosen.append(int(np.argmin(d)))
    return chosen


def sequential_design(pool_kappa: np.ndarray, score: np.ndarray, start: list[int], n: int, criterion: str,
                      settings: dict) -> list[int]:
    """``start`` grown to n pool indices, one at a time, by ``criterion`` (variance | ei) on a Kriging
    model of ``score`` (the per-geometry zeta_max) refitted after every addition."""
    if criterion not in ("variance", "ei"):
        raise ValueError(f"sequential criterion {criterion!r}: choose 'variance' or 'ei'")
    chosen = list(start)
    while len(chosen) < n:
        model, _ = fit_model(pool_kappa[chosen], score[chosen], settings, name="zeta_max")
        rest = np.setdiff1d(np.arange(len(pool_kappa)), chosen)
        mu, sd = model.predict(pool_kappa[rest])
        sd = np.maximum(np.asarray(sd, float), 1e-300)
        if criterion == "variance":
            gain = sd
        else:
            u = (mu - score[chosen].max()) / sd
            gain = (mu - score[chosen].max()) * norm.cdf(u) + sd * norm.pdf(u)
        chosen.append(int(rest[np.argmax(gain)]))
    return chosen


def validation_errors(dataset: xr.Dataset, train_gids, settings: dict, levels, gammas,
                      max_level) -> tuple[dict, float]:
    """Fit the campaign surrogate on ``train_gids``; RMS relative error of each user quantity over the
    validation geometries, and the fit's CPU time (s)."""
    mask = usable_mask(dataset) & dataset.geometry.isin(list(train_gids))
    cpu = time.process_time()
    surrogate = KrigingSurrogate(fit_campaign(dataset, mask=mask, settings=settings))
    fit_cpu = time.process_time() - cpu
    val = dataset.isel(geometry=(dataset.split == "validation").values)
    bb = backbones(surrogate, kappa_of(val), with_std=False)
    errors: dict[str, list] = {}
    for j, gid in enumerate(val.geometry.values):
        ref = computed_quantities(dataset, gid, levels, gammas, max_level)
        pred = user_quantities(backbone_dataset(bb.amplitude, bb.mean["q_res_z"][:, j], bb.mean["zeta"][:, j],
                                                bb.mean["omega0"][:, j], bb.mean["gamma"][:, j]), levels, gammas,
                               max_level)
        for k, r in ref.items():
            if np.isfinite(r):
                e = abs(pred[k] / r - 1.0) if np.isfinite(pred[k]) else 1.0
                errors.setdefault(k, []).append(e)
    return {k: float(np.sqrt(np.mean(np.square(v)))) for k, v in errors.items()}, fit_cpu


def training_size_study(dataset: xr.Dataset, sizes, surrogate_cfg: dict, levels, gammas, max_level,
                        seed: int) -> list[dict]:
    """Rows (design, n, error_<quantity>, fit_cpu_s, geometries) for every design and size."""
    settings = {**surrogate_cfg, "min_training": min(min(sizes), surrogate_cfg["min_training"])}
    pool = dataset.isel(geometry=(dataset.split == "training").values)
    pool_gids = pool.geometry.values
    pool_kappa = kappa_of(pool)
    score = np.array([computed_quantities(dataset, g, levels, gammas, max_level)["zeta_max"] for g in pool_gids])
    ok = np.isfinite(score)
    pool_gids, pool_kappa, score = pool_gids[ok], pool_kappa[ok], score[ok]
    sizes = sorted(min(int(n), len(pool_gids)) for n in sizes)
    start = lhs_design(pool_kappa, sizes[0], seed)
    rows = []
    for design in DESIGNS:
        grown = (sequential_design(pool_kappa, score, start, sizes[-1], design, settings)
                 if design != "lhs" else None)
        for n in sizes:
            idx = lhs_design(pool_kappa, n, seed) if design == "lhs" else grown[:n]
            err, fit_cpu = validation_errors(dataset, pool_gids[idx], settings, levels, gammas, max_level)
            rows.append({"design": design, "n": n, **{f"error_{k}": v for k, v in err.items()},
                         "error_max": max(err.values()), "fit_cpu_s": fit_cpu,
                         "geometries": " ".join(pool_gids[idx])})
    return rows
