"""The surrogates of a round: fitted on the round's training rings, read through their predictive mean
and standard deviation, judged by their leave-one-out errors.

:func:`fit_surrogate` is the one place that chooses the model: the campaign's per-amplitude Kriging
(:func:`~ringdamper.campaign.kriging.fit_campaign`, the ``surrogate`` settings), so that a round reads
exactly the model the campaign reports. Everything else reads predictions through
:func:`~ringdamper.campaign.exploration.backbones` of the returned ``surrogate`` (mean and standard
deviation of |q_res,z|, omega0, zeta, gamma at every modal amplitude).

Normalised leave-one-out error of output o, pooled over the amplitudes a of its Gaussian-process models
(eᵢ the leave-one-out residuals of :mod:`~ringdamper.campaign.kriging.gp`, ȳₐ the training mean):

    ε_o = √( Σₐ Σᵢ eₐᵢ² / Σₐ Σᵢ (yₐᵢ - ȳₐ)² )     (= √(1 - Q²) for a single amplitude).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import xarray as xr

from ..kriging import OUTPUTS, STATUS_GP, KrigingSurrogate, fit_campaign


@dataclass
class RoundModels:
    """The fitted models (``kriging``: the kriging.nc Dataset) and their predictor (``surrogate``)."""

    kriging: xr.Dataset
    surrogate: KrigingSurrogate


def fit_surrogate(dataset: xr.Dataset, mask: xr.DataArray, settings: dict, workers: int = 1) -> RoundModels:
    """The models of every output and amplitude on the usable points ``mask`` of ``dataset``."""
    kriging = fit_campaign(dataset, mask=mask, settings=settings, workers=workers)
    return RoundModels(kriging, KrigingSurrogate(kriging))


def normalised_loo(kriging: xr.Dataset, outputs=OUTPUTS) -> dict:
    """output -> ε_o (module docstring), NaN when no amplitude has a Gaussian-process model."""
    errors = {}
    for io, out in enumerate(outputs):
        gp = kriging["status"].values[io] == STATUS_GP
        y = kriging[out].transpose("amplitude", "geometry").values[gp]
        e = kriging[f"{out}_loo_residual"].transpose("amplitude", "geometry").values[gp]
        spread = np.nansum((y - np.nanmean(y, axis=1, keepdims=True)) ** 2)
        errors[out] = float(np.sqrt(np.nansum(e ** 2) / spread)) if gp.any() and spread > 0 else float("nan")
    return errors


def training_spread(kriging: xr.Dataset, outputs=OUTPUTS) -> dict:
    """output -> (amplitude,) standard deviation of the training values (NaN where not fitted): the
    scale that makes the outputs' predictive uncertainties comparable."""
    return {out: np.nanstd(kriging[out].transpose("amplitude", "geometry").values, axis=1) for out in outputs}
