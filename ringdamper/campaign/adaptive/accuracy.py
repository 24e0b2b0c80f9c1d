"""Estimates of the validation error of a round's surrogates from training-side evidence alone.

The validation rings sample the domain [-1, 1]³ evenly (maximin LHS), so the RMSE they measure for
output o, pooled over its amplitudes a, estimates the root of the domain average of the squared error,

    RMSE_o = √( mean_a ∫ (y_o(a, x) - ŷ_o(a, x))² dx ).

Estimates of it, each on a fixed set X of ``DOMAIN_POINTS`` scrambled Sobol' points (the same every
round, so that the estimate moves only with the models):

* ``variance``: the predictive variance over the domain, √(mean_a mean_{x∈X} s_o(a, x)²), s_o the
  calibrated predictive spread of the model (:mod:`~ringdamper.campaign.kriging.gp`, *variance
  calibration*; (upper - lower) / 4 in output units);
* ``loo``: the leave-one-out residuals eᵢ of the training rings, √(mean_a mean_i e_aᵢ²);
* ``voronoi``: the same residuals weighted by the share of the domain nearest to each ring,
  √(mean_a Σᵢ w_aᵢ e_aᵢ²), w_aᵢ the fraction of X whose nearest training ring (among those that train
  amplitude a) is i: an adaptive design's rings crowd where the response is hardest, and each residual
  then speaks for the small cell around it only.

Each is divided by the output's spread over the domain, S_o = √(mean_a var_{x∈X} ŷ_o(a, x)) (the
predicted means, pooled within amplitudes), so that it compares with a tolerance relative to the
output's variation: docs/adaptive.md, *Stopping rule*, says which estimate the rule reads and why.
"""
from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree
from scipy.stats import qmc

from ..design_space import N_KAPPA
from ..exploration import Backbones, backbones
from ..kriging import OUTPUTS, STATUS_UNFITTED

DOMAIN_POINTS = 1024  # Sobol' points of the domain average (a power of 2)
DOMAIN_STREAM = 101  # their random stream, apart from the design's (INITIAL_STREAM) and the rounds' (round + 1)
#: Digits an estimate is recorded and compared with (:func:`estimates`).
SIGNIFICANT_DIGITS = 10
ESTIMATES = ("variance", "loo", "voronoi")
RULE_ESTIMATE = "variance"  # the one the stop rule reads (docs/adaptive.md, *Stopping rule*)


def domain_points(seed: int) -> np.ndarray:
    """(DOMAIN_POINTS, 3) scrambled Sobol' points in [-1, 1]³, seeded by (``seed``, DOMAIN_STREAM)."""
    sobol = qmc.Sobol(d=N_KAPPA, scramble=True, rng=np.random.default_rng([seed, DOMAIN_STREAM]))
    return 2.0 * sobol.random_base2(int(np.log2(DOMAIN_POINTS))) - 1.0


def domain_spread(bb: Backbones, outputs=OUTPUTS) -> dict:
    """output -> S_o (module docstring): the spread of the predicted means over the points of ``bb``."""
    out = {}
    for name in outputs:
        mean = bb.mean[name]
        fitted = np.all(np.isfinite(mean), axis=1)
        out[name] = float(np.sqrt(np.mean(np.var(mean[fitted], axis=1)))) if fitted.any() else float("nan")
    return out


def variance_rmse(bb: Backbones, outputs=OUTPUTS) -> dict:
    """output -> √(mean_a mean_x s_o(a, x)²) over the points of ``bb`` (the ``variance`` estimate)."""
    out = {}
    for name in outputs:
        s = bb.std[name]
        fitted = np.all(np.isfinite(s), axis=1)
        out[name] = float(np.sqrt(np.mean(s[fitted] ** 2))) if fitted.any() else float("nan")
    return out


def cell_weights(kriging, points: np.ndarray) -> np.ndarray:
    """(amplitude, geometry) w_aᵢ: the fraction of ``points`` whose nearest training ring of amplitude
    a (``training_mask`` of the kriging.nc Dataset) is ring i; 0 for a ring that does not train a."""
    kappa = kriging["kappa"].transpose("geometry", "parameter").values
    mask = kriging["training_mask"].transpose("amplitude", "geometry").values.astype(bool)
    weights = np.zeros(mask.shape)
    cache = {}
    for ia, rows in enumerate(mask):
        key = rows.tobytes()
        if key not in cache:
            idx = np.flatnonzero(rows)
            nearest = cKDTree(kappa[idx]).query(points)[1] if idx.size else np.empty(0, int)
            cache[key] = np.bincount(idx[nearest], minlength=len(kappa)) / len(points) if idx.size else 0.0
        weights[ia] = cache[key]
    return weights


def loo_rmse(kriging, weights: np.ndarray | None = None, outputs=OUTPUTS) -> dict:
    """output -> the leave-one-out RMSE pooled over its fitted amplitudes: plain (``loo``) or with the
    (amplitude, geometry) ``weights`` of :func:`cell_weights` (``voronoi``)."""
    out = {}
    for io, name in enumerate(outputs):
        fitted = kriging["status"].values[io] != STATUS_UNFITTED
        e = kriging[f"{name}_loo_residual"].transpose("amplitude", "geometry").values[fitted]
        if not fitted.any():
            out[name] = float("nan")
        elif weights is None:
            out[name] = float(np.sqrt(np.nanmean(e ** 2)))
        else:
            w = weights[fitted]
            out[name] = float(np.sqrt(np.mean(np.nansum(w * e ** 2, axis=1) / w.sum(axis=1))))
    return out


def estimates(models, points: np.ndarray, outputs=OUTPUTS) -> dict:
    """estimate -> output -> the RMSE estimate divided by S_o (module docstring), and ``spread`` ->
    output -> S_o, for the surrogates ``models`` (:class:`.model.RoundModels`) on ``points``, each to
    :data:`SIGNIFICANT_DIGITS`: the predictions over the domain's points are summed in parallel
    (differently on one core and on two, at 1e-14), and an estimate means no more digits than these, so
    a round's record and its stop decision are the same on any number of cores."""
    bb = backbones(models.surrogate, points, outputs)
    spread = domain_spread(bb, outputs)
    raw = {"variance": variance_rmse(bb, outputs), "loo": loo_rmse(models.kriging, outputs=outputs),
           "voronoi": loo_rmse(models.kriging, cell_weights(models.kriging, points), outputs)}
    ratios = {k: {o: _significant(v[o] / spread[o]) for o in outputs} for k, v in raw.items()}
    return {"spread": {o: _significant(v) for o, v in spread.items()}, **ratios}


def _significant(x: float) -> float:
    return float(f"{x:.{SIGNIFICANT_DIGITS}g}")
