"""The surrogates of a round: fitted on the round's training rings, read through their predictive mean
and standard deviation.

:func:`fit_surrogate` is the one place that chooses the model: the campaign's per-amplitude Kriging
(:func:`~ringdamper.campaign.kriging.fit_campaign`, the ``surrogate`` settings), so that a round reads
exactly the model the campaign reports. Everything else reads predictions through
:func:`~ringdamper.campaign.exploration.backbones` of the returned ``surrogate`` (mean and standard
deviation of |q_res,z|, omega0, zeta, gamma at every modal amplitude).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import xarray as xr

from ..kriging import OUTPUTS, KrigingSurrogate, fit_campaign


@dataclass
class RoundModels:
    """The fitted models (``kriging``: the kriging.nc Dataset) and their predictor (``surrogate``)."""

    kriging: xr.Dataset
    surrogate: KrigingSurrogate


def fit_surrogate(dataset: xr.Dataset, mask: xr.DataArray, settings: dict, workers: int = 1) -> RoundModels:
    """The models of every output and amplitude on the usable points ``mask`` of ``dataset``."""
    kriging = fit_campaign(dataset, mask=mask, settings=settings, workers=workers)
    return RoundModels(kriging, KrigingSurrogate(kriging))


def training_spread(kriging: xr.Dataset, outputs=OUTPUTS) -> dict:
    """output -> (amplitude,) standard deviation of the training values (NaN where not fitted): the
    scale that makes the outputs' predictive uncertainties comparable."""
    return {out: np.nanstd(kriging[out].transpose("amplitude", "geometry").values, axis=1) for out in outputs}
