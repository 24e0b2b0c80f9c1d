"""The stop rule on a recorded campaign history (data/adaptive_history.nc, made by tools/stop_history.py
from a fresh-clone default campaign: its 60 training rings with the round that chose each, rounds 1-6,
the last stopped by the ring budget, and its 20 validation rings), replayed round by round
(ringdamper.campaign.adaptive.replay): each round chooses the rings the campaign chose, the rule stops
where the validation RMSE first meets the tolerance, give or take one round, and held points moved
within the solver's tolerance leave the stop round and the ring count as they were."""
from pathlib import Path

import numpy as np
import pytest

from ringdamper.campaign.adaptive.replay import replay
from ringdamper.campaign.adaptive.stopping import CONVERGED
from ringdamper.campaign.kriging import OUTPUTS
from ringdamper.config import load_config
from ringdamper.io import read_netcdf

from .held import moved_held

DATA = Path(__file__).parent / "data" / "adaptive_history.nc"
CONFIG = load_config(Path(__file__).parents[2] / "config.yaml")
TOLERANCE = CONFIG["sampling"]["adaptive"]["rmse_tolerance"]
ROUNDS_OFF = 1  # the rule stops at most this many rounds from where the validation RMSE first meets the tolerance
KAPPA_ATOL = 1e-9  # the history's kappa are samples.csv's, to 10 significant digits

pytestmark = pytest.mark.xdist_group("adaptive_history")


def stop_of(records: list[dict]) -> tuple | None:
    """Round, training rings and reason of the first record that stops (the replay runs every recorded
    round); None if none does."""
    return next(((r["round"], r["n_computed"], r["reason"]) for r in records if r["stop"]), None)


def validation_meets(records: list[dict]) -> int | None:
    """The first round whose models' validation error is within the tolerance for every output."""
    return next((r["round"] for r in records if all(r["validation"][o] <= TOLERANCE[o] for o in OUTPUTS)), None)


@pytest.fixture(scope="module")
def history():
    return read_netcdf(DATA)


@pytest.fixture(scope="module")
def replayed(history):
    return replay(history, CONFIG)


def test_each_replayed_round_chooses_the_rings_the_campaign_chose(history, replayed):
    """Every round but the last (whose choice, if the replayed rule goes on, the history does not hold),
    as a set: a round's rings are computed together and their order, by acquisition score, only names
    them; two of round 4's six have scores that the campaign's fit and the replay's rank either way."""
    for record in replayed[:-1]:
        recorded = history.isel(geometry=(history["round"] == record["round"]).values)
        chosen = np.array([c["kappa"] for c in record["chosen"]]).reshape(-1, 3)
        expected = np.column_stack([recorded[f"kappa{i}"].values for i in (1, 2, 3)])
        np.testing.assert_allclose(np.unique(chosen, axis=0), np.unique(expected, axis=0), rtol=0,
                                   atol=KAPPA_ATOL, err_msg=f"round {record['round']}")


def test_the_rule_stops_where_the_validation_error_first_meets_the_tolerance(replayed):
    """The round the rule stops at by its accuracy and stability, and the first round whose validation
    error meets the tolerance, each counted as the round after the history's last when it is not in
    the history (a stop at the budget is no such stop), are at most ROUNDS_OFF apart."""
    beyond = replayed[-1]["round"] + 1
    stop = next((r["round"] for r in replayed if r["stop"] and r["reason"] == CONVERGED), beyond)
    met = validation_meets(replayed) or beyond
    assert abs(stop - met) <= ROUNDS_OFF, [(r["round"], r["ratios"], r["validation"]) for r in replayed]


@pytest.mark.parametrize("sign", [1.0])
def test_held_points_moved_within_the_solver_tolerance_leave_the_stop_as_it_was(history, replayed, sign):
    """Every held training point's zeta and gamma moved by the solver's tolerance
    (:func:`.held.moved_held`): the replay on the same rings stops at the same round, with the same
    number of training rings and for the same reason."""
    moved, n_held = moved_held(history, (history.split == "training").values, sign)
    assert n_held >= 10
    after = replay(moved, CONFIG)
    assert stop_of(after) == stop_of(replayed), [(r["round"], r["ratios"], r["optimum_changes"]) for r in after]
