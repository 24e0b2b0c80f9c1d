"""The stop rule's estimate of the validation error on the campaign's own rings (data/adaptive_rings.nc:
39 rings of the default campaign, initial-design and validation rings, made by tools/stop_history.py):
on seeded random splits (26 rings train, the others validate) the estimate predicts the validation
RMSE within a stated factor, and training values moved within the solver's tolerance at the held
points (status 3) move it by less than a stated share and leave the accuracy decision as it was."""
from pathlib import Path

import numpy as np
import pytest

from ringdamper.campaign.adaptive.accuracy import RULE_ESTIMATE, domain_points, estimates
from ringdamper.campaign.adaptive.model import fit_surrogate
from ringdamper.campaign.adaptive.stopping import accuracy_ratios
from ringdamper.campaign.dataset import kappa, usable_mask
from ringdamper.campaign.exploration import backbones
from ringdamper.campaign.kriging import OUTPUTS
from ringdamper.config import load_config
from ringdamper.io import read_netcdf

from .held import moved_held

DATA = Path(__file__).parent / "data" / "adaptive_rings.nc"
CONFIG = load_config(Path(__file__).parents[2] / "config.yaml")
SETTINGS = {**CONFIG["surrogate"], "min_training": 12}  # 26 training rings: every amplitude is fitted
N_TRAIN, SPLITS = 26, (0, 1, 2)
ESTIMATE_FACTOR = 2.0  # measured 0.50-1.43 on six splits of 18 (docs/investigations/2026-12-01-stop-rule-estimate.md)
ESTIMATE_SHIFT = 0.05  # the estimates move by at most 5 % (relative) under that perturbation

pytestmark = pytest.mark.xdist_group("adaptive_rings")


def split_of(ds, seed: int) -> np.ndarray:
    """(geometry,) True for the N_TRAIN training rings of split ``seed``."""
    train = np.zeros(ds.sizes["geometry"], bool)
    train[np.random.default_rng(seed).choice(ds.sizes["geometry"], N_TRAIN, replace=False)] = True
    return train


def fitted(ds, train: np.ndarray) -> dict:
    """The rule's relative estimates and the validation RMSE relative to the same spread."""
    sub = ds.isel(geometry=train)
    models = fit_surrogate(sub, usable_mask(sub), SETTINGS)
    est = estimates(models, domain_points(CONFIG["sampling"]["seed"]))
    val = ds.isel(geometry=~train)
    ok = usable_mask(val).values
    bb = backbones(models.surrogate, kappa(val), OUTPUTS, with_std=False)
    rmse = {o: float(np.sqrt(np.mean((val[o].values - bb.mean[o].T)[ok] ** 2))) for o in OUTPUTS}
    return {"estimate": est[RULE_ESTIMATE], "validation": {o: rmse[o] / est["spread"][o] for o in OUTPUTS}}


@pytest.fixture(scope="module")
def rings():
    return read_netcdf(DATA)


@pytest.fixture(scope="module")
def recorded(rings):
    return [fitted(rings, split_of(rings, seed)) for seed in SPLITS]


def test_the_estimate_predicts_the_validation_error_within_a_factor(recorded):
    ratios = np.array([[r["estimate"][o] / r["validation"][o] for o in OUTPUTS] for r in recorded])
    assert np.all((ratios >= 1 / ESTIMATE_FACTOR) & (ratios <= ESTIMATE_FACTOR)), ratios


@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_held_points_moved_within_the_solver_tolerance_barely_move_the_estimate(rings, recorded, sign):
    """Every held training point's zeta and gamma moved by the solver's tolerance (:func:`.held.moved_held`,
    both sign patterns), split 0: each estimate within ESTIMATE_SHIFT of its value, and
    each output on the same side of its tolerance as before."""
    train = split_of(rings, SPLITS[0])
    moved, n_held = moved_held(rings, train, sign)
    assert n_held >= 10
    after, before = fitted(moved, train)["estimate"], recorded[0]["estimate"]
    shift = {o: after[o] / before[o] - 1 for o in OUTPUTS}
    assert all(abs(v) <= ESTIMATE_SHIFT for v in shift.values()), shift
    tolerance = CONFIG["sampling"]["adaptive"]["rmse_tolerance"]
    assert ({o: r <= 1 for o, r in accuracy_ratios(after, tolerance).items()}
            == {o: r <= 1 for o, r in accuracy_ratios(before, tolerance).items()})
