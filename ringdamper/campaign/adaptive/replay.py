"""The rounds of a recorded adaptive campaign replayed, each judged on the validation rings.

A recorded history (``tools/stop_history.py``: the training and validation rings of a finished
campaign, each training ring with the round that chose it, 0 for the initial design) holds what every
round fitted: round k fits the training rings of rounds < k. :func:`replay` runs
:func:`.rounds.plan_round` on exactly those rings, round after round, with the replayed records as the
earlier rounds' history (the campaign's own loop, the rings given instead of computed: the rings a
round chooses in the replay are those it chose in the campaign when the values are the campaign's),
and adds to each record the validation error of the round's models,

    e_o = RMSE_o / S_o^val,

RMSE_o the campaign's validation RMSE of output o on the validation rings
(:func:`~ringdamper.campaign.validation.validate`) and S_o^val = √(mean_a var_i y_o(a, i)) the spread
of the validation rings' own values, pooled within amplitudes: the measure the stop rule's
``rmse_tolerance`` is set in (docs/adaptive.md, *Stopping rule*).
"""
from __future__ import annotations

import numpy as np
import xarray as xr

from ..dataset import kappa, usable_mask
from ..kriging import OUTPUTS
from ..validation import metrics_table, validate
from .model import RoundModels
from .rounds import plan_round, round_models


def pooled_spread(values: np.ndarray, ok: np.ndarray) -> float:
    """√(mean over amplitudes of the variance over the usable rings): ``values``, ``ok`` (geometry, amplitude)."""
    var = [np.var(values[ok[:, a], a]) for a in range(values.shape[1]) if ok[:, a].sum() > 1]
    return float(np.sqrt(np.mean(var)))


def validation_error(models: RoundModels, rings: xr.Dataset, mask: xr.DataArray) -> dict:
    """output -> e_o (module docstring) of ``models`` on the validation rings of ``rings`` (usable
    points ``mask``)."""
    table = metrics_table(validate(models.kriging, models.surrogate, rings, mask))
    val = (rings.split == "validation").values
    ok = mask.isel(geometry=val).values
    return {o: float(table.loc[o, "rmse"]) / pooled_spread(
        rings[o].isel(geometry=val).transpose("geometry", "amplitude").values, ok) for o in OUTPUTS}


def round_rings(history: xr.Dataset, round_: int) -> xr.Dataset:
    """The training rings round ``round_`` fits, in the campaign's order (initial design, then the rings
    of each round in the order chosen)."""
    training = (history.split == "training").values & (history["round"].values < round_)
    idx = np.flatnonzero(training)
    order = np.lexsort((history.geometry.values[idx].astype(str), history["round"].values[idx]))
    return history.isel(geometry=idx[order])


def replay(history: xr.Dataset, config: dict, rounds: int | None = None, workers: int = 1) -> list[dict]:
    """The records of rounds 1 .. ``rounds`` (default: every recorded round, the last chosen ring's
    round + 1) replayed on ``history`` (module docstring), each with ``validation``: output -> e_o.
    ``config``: the sampling, surrogate and exploration sections of the campaign's configuration."""
    mask = usable_mask(history)
    validation = (history.split == "validation").values
    last = int(history["round"].values[~validation].max()) + 1 if rounds is None else rounds
    records: list[dict] = []
    for k in range(1, last + 1):
        rings = round_rings(history, k)
        ring_mask = mask.sel(geometry=rings.geometry)
        models = round_models(rings, ring_mask, config, workers)
        record = plan_round(rings, ring_mask, records, config, k, kappa(history.isel(geometry=validation)),
                            workers, models)
        record["validation"] = validation_error(models, history, mask)
        records.append(record)
    return records
