"""The adaptive design through the library code the rules call (ringdamper.campaign.adaptive): on
analytic backbones whose peak damping has its maximum on an edge of the box, or on a narrow ridge, the
loop finds the maximum within 1 % and stops by its own rule, with at most half the evaluations a
maximin LHS of the same accuracy needs; the same seed gives the same rings bitwise; the batch rule,
the stop rule, the failure rules and the configuration checks."""
import copy
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from ringdamper.campaign.adaptive.batch import select_batch
from ringdamper.campaign.adaptive.design import candidates
from ringdamper.campaign.adaptive.model import fit_surrogate
from ringdamper.campaign.adaptive.rounds import RoundFailedError, predicted_optimum, run_loop, training_dataset
from ringdamper.campaign.adaptive.stopping import BUDGET, CONVERGED, decide
from ringdamper.campaign.design_space import maximin_lhs
from ringdamper.campaign.sampling import make_samples
from ringdamper.config import ConfigError, validate_config
from ringdamper.io import write_netcdf
from tests.campaign.synthetic import dnnm_dataset

DATA = Path(__file__).parent / "data"
ALPHA = np.geomspace(1e-5, 1e-4, 5)
TOL = 0.6  # relative error the analytic loop may stop at (rmse_tolerance of every output)
TOLERANCE = 0.01  # the optimum's true peak damping within 1 % of the maximum
EDGE = np.array([1.0, -1.0, 0.3])  # on the edge kappa1 = +1, kappa2 = -1


def edge_peak(k):
    """Peak damping largest on an edge of the box: a Gaussian bump of width 0.35 at EDGE."""
    return 3e-3 * (0.3 + 0.7 * np.exp(-np.sum((k - EDGE) ** 2) / (2 * 0.35 ** 2)))


def ridge_peak(k):
    """Peak damping on a narrow ridge kappa1 + kappa2 = 0.5 (width 0.25), slowly varying along it;
    largest at (0.35, 0.15, 0.4)."""
    return 3e-3 * (0.3 + 0.7 * np.exp(-(k[0] + k[1] - 0.5) ** 2 / (2 * 0.25 ** 2)
                                      - ((k[0] - k[1] - 0.2) ** 2 + (k[2] - 0.4) ** 2) / (2 * 0.6 ** 2)))


PEAKS = {"edge": (edge_peak, EDGE), "ridge": (ridge_peak, np.array([0.35, 0.15, 0.4]))}

CONFIG = {"sampling": {"seed": 3, "factorial_levels": [-1.0, 1.0], "n_lhs_training": 0, "n_lhs_validation": 3,
                       "named_validation": [], "lhs_candidates": 20, "min_distance": 0.05, "design": "adaptive",
                       "adaptive": {"n_initial": 10, "initial_seed": 0, "batch": 3, "n_max": 60,
                                    "n_candidates": 1024, "exploit_weight": 1.0, "batch_spacing": 0.15,
                                    "rmse_tolerance": dict.fromkeys(("q_res_z", "omega0", "zeta", "gamma"), TOL),
                                    "kappa_tolerance": 0.1, "zeta_tolerance": 0.01, "stable_rounds": 2}},
          "surrogate": {"min_training": 8, "n_starts": 4},
          "exploration": {"optimum_max_level": 1.0}}


def evaluator(root, peak):
    """evaluate(table) -> gid -> dnnm.nc of the analytic backbones (tests/campaign/synthetic.py)."""
    def evaluate(table):
        paths = {}
        for row in table.itertuples():
            path = root / row.gid / "dnnm.nc"
            write_netcdf(dnnm_dataset([row.kappa1, row.kappa2, row.kappa3], ALPHA, zeta_peak=peak), path)
            paths[row.gid] = path
        return paths
    return evaluate


def lhs_optimum(root, peak, n, seed):
    """The predicted optimum of the same surrogates fitted on an ``n``-point maximin LHS."""
    points = maximin_lhs(n, np.empty((0, 3)), np.random.default_rng(seed), 20)
    table = pd.DataFrame([(f"t{i:03d}", *k, "training") for i, k in enumerate(points)],
                         columns=["gid", "kappa1", "kappa2", "kappa3", "split"])
    ds, mask = training_dataset(table, [], evaluator(root, peak)(table))
    models = fit_surrogate(ds, mask, CONFIG["surrogate"])
    return np.array(predicted_optimum(models.surrogate, candidates(CONFIG["sampling"], 1, np.empty((0, 3))),
                                      1.0)["kappa"])


@pytest.fixture(scope="module", params=list(PEAKS))
def loop(request, tmp_path_factory):
    peak, argmax = PEAKS[request.param]
    root = tmp_path_factory.mktemp(request.param)
    table, records = run_loop(evaluator(root, peak), CONFIG)
    return request.param, root, table, records


def test_the_loop_finds_the_maximum_and_stops_by_its_rule(loop):
    name, _, table, records = loop
    peak, argmax = PEAKS[name]
    last = records[-1]
    assert last["stop"] and last["reason"] == "converged", [(r["n_computed"], r["loo"]) for r in records]
    assert len(records) >= 3 and last["n_computed"] < CONFIG["sampling"]["adaptive"]["n_max"]
    assert peak(np.array(last["optimum"]["kappa"])) >= (1 - TOLERANCE) * peak(argmax)
    assert (table.split == "training").sum() == last["n_computed"]
    for record in records[:-1]:        # each round's batch: b rings, each with its acquisition values
        assert len(record["chosen"]) == CONFIG["sampling"]["adaptive"]["batch"]
        assert all(c["score"] > 0 and c["explore"] >= 0 and c["exploit"] >= 0 for c in record["chosen"])


def test_an_lhs_needs_more_than_twice_the_evaluations_for_the_same_accuracy(loop):
    """Maximin LHS of 2 n - 1 points (n the loop's evaluations), three seeds: none is within 1 %."""
    name, root, _, records = loop
    peak, argmax = PEAKS[name]
    n = 2 * records[-1]["n_computed"] - 1
    ratios = [peak(lhs_optimum(root / f"lhs{seed}", peak, n, seed)) / peak(argmax) for seed in range(3)]
    assert max(ratios) < 1 - TOLERANCE, ratios


def test_the_same_seed_gives_the_same_rings_bitwise(loop, tmp_path):
    name, _, table, _ = loop
    again, _ = run_loop(evaluator(tmp_path, PEAKS[name][0]), copy.deepcopy(CONFIG))
    kappa = ["kappa1", "kappa2", "kappa3"]
    assert again.gid.tolist() == table.gid.tolist()
    assert again[kappa].to_numpy().tobytes() == table[kappa].to_numpy().tobytes()


def test_a_batch_is_spread_by_the_distance_rule():
    rng = np.random.default_rng(0)
    points = rng.uniform(-1, 1, (500, 3))
    score = -np.linalg.norm(points - 0.5, axis=1)   # every best candidate crowds around (0.5, 0.5, 0.5)
    existing = np.array([[0.5, 0.5, 0.5]])
    picked = select_batch(points, score, existing, 6, 0.3)
    chosen = points[picked]
    assert len(picked) == 6 and len(set(picked)) == 6
    d = np.linalg.norm(chosen[:, None] - np.vstack([chosen, existing])[None], axis=2)
    assert np.all(d[~np.eye(6, 7, dtype=bool)] >= 0.3)


def test_the_budget_stops_the_loop_without_an_error():
    adaptive = CONFIG["sampling"]["adaptive"]
    optima = [{"kappa": [0.0, 0.0, 0.0], "zeta_max": 1e-3}, {"kappa": [0.5, 0.0, 0.0], "zeta_max": 2e-3}]
    going = decide({"zeta": 2 * TOL}, optima, adaptive["n_max"] - 1, adaptive)
    assert not going["stop"]
    stopped = decide({"zeta": 2 * TOL}, optima, adaptive["n_max"], adaptive)
    assert stopped["stop"] and stopped["reason"] == BUDGET and stopped["worst_ratio"] == pytest.approx(2.0)


def test_the_loop_stops_when_every_estimate_meets_its_tolerance_and_the_optimum_has_settled():
    """zeta and gamma within their tolerances, q_res_z just over its own: not accurate; at its
    tolerance: converged; an optimum that moved by 0.2 in kappa1 last round: not stable."""
    adaptive = {**CONFIG["sampling"]["adaptive"], "rmse_tolerance": {"q_res_z": 0.1, "zeta": 0.05, "gamma": 0.2}}
    optima = [{"kappa": [1.0, -1.0, -1.0], "zeta_max": 2e-3}] * 3
    over = decide({"q_res_z": 0.1001, "zeta": 0.04, "gamma": 0.1}, optima, 48, adaptive)
    assert not over["stop"] and not over["accurate"] and over["stable"]
    assert over["ratios"] == pytest.approx({"q_res_z": 1.001, "zeta": 0.8, "gamma": 0.5})
    met = decide({"q_res_z": 0.1, "zeta": 0.04, "gamma": 0.1}, optima, 48, adaptive)
    assert met["stop"] and met["reason"] == CONVERGED
    moving = optima[:-1] + [{"kappa": [0.8, -1.0, -1.0], "zeta_max": 2e-3}]
    assert not decide({"q_res_z": 0.1, "zeta": 0.04, "gamma": 0.1}, moving, 48, adaptive)["stop"]
    assert not decide({"q_res_z": 0.1, "zeta": 0.04, "gamma": 0.1}, optima[:2], 42, adaptive)["stop"]


def test_an_output_without_a_tolerance_is_an_error_naming_it():
    with pytest.raises(ValueError, match=r"rmse_tolerance lacks \['phi'\]"):
        decide({"zeta": 0.01, "phi": 0.01}, [{"kappa": [0.0] * 3, "zeta_max": 1e-3}], 30,
               CONFIG["sampling"]["adaptive"])


def test_a_failed_ring_is_excluded_and_a_round_of_failures_is_an_error_naming_them(tmp_path):
    samples = make_samples(CONFIG["sampling"])
    training = samples[samples.split == "training"]
    paths = evaluator(tmp_path, edge_peak)(training)
    chosen = [{"gid": "a01_000", "kappa": [0.1, 0.2, 0.3]}, {"gid": "a01_001", "kappa": [0.3, 0.2, 0.1]}]
    record = {"round": 1, "chosen": chosen}
    failed = np.full(ALPHA.size, 99)
    for i, c in enumerate(chosen):
        paths[c["gid"]] = tmp_path / c["gid"] / "dnnm.nc"
        write_netcdf(dnnm_dataset(c["kappa"], ALPHA, status=failed if i == 0 else None), paths[c["gid"]])
    ds, mask = training_dataset(samples, [record], paths)
    assert not mask.sel(geometry="a01_000").any() and mask.sel(geometry="a01_001").all()
    write_netcdf(dnnm_dataset(chosen[1]["kappa"], ALPHA, status=failed), paths["a01_001"])
    with pytest.raises(RoundFailedError, match=r"every ring of round 1 failed: a01_000 .*; a01_001"):
        training_dataset(samples, [record], paths)


def test_the_paper_design_gives_the_paper_samples_bitwise(campaign_config, small_config):
    for config, name in ((campaign_config, "paper_samples.csv"), (small_config, "paper_samples_small.csv")):
        sampling = {**config["sampling"], "design": "paper"}
        text = make_samples(sampling).to_csv(index=False, float_format="%.10g", lineterminator="\n")
        assert text == (DATA / name).read_text()


def test_both_designs_keep_the_validation_and_reference_rings(campaign_config):
    paper = make_samples({**campaign_config["sampling"], "design": "paper"})
    adaptive = make_samples({**campaign_config["sampling"], "design": "adaptive"})
    columns = ["gid", "kappa1", "kappa2", "kappa3"]
    assert adaptive[adaptive.split == "validation"][columns].reset_index(drop=True).equals(
        paper[paper.split == "validation"][columns].reset_index(drop=True))
    reference = [(0, 0, 0), (1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1), (1, -1, -1)]
    k = adaptive[["kappa1", "kappa2", "kappa3"]].to_numpy()
    assert all(np.all(k == r, axis=1).any() for r in reference)


@pytest.mark.parametrize("key, value, message", [
    ("batch", 0, "sampling.adaptive.batch = 0 is out of range: allowed [1, 1000]"),
    ("n_initial", 20, "sampling.adaptive.n_initial = 20 is below surrogate.min_training = 25"),
    ("n_max", 29, "sampling.adaptive.n_max = 29 is below sampling.adaptive.n_initial = 30"),
    ("rmse_tolerance", {"q_res_z": 0.1, "omega0": 0.1, "zeta": 0.0, "gamma": 0.1},
     "sampling.adaptive.rmse_tolerance.zeta = 0.0 is out of range: allowed (0, +inf)"),
    ("initial_seed", -1, "sampling.adaptive.initial_seed = -1 is out of range: allowed [0, +inf)"),
    ("kappa_tolerance", -0.1, "sampling.adaptive.kappa_tolerance = -0.1 is out of range: allowed (0, +inf)"),
    ("zeta_tolerance", 0.0, "sampling.adaptive.zeta_tolerance = 0.0 is out of range: allowed (0, +inf)"),
])
def test_a_bad_adaptive_setting_is_refused_naming_the_field(config, key, value, message):
    config["sampling"]["adaptive"][key] = value
    with pytest.raises(ConfigError) as err:
        validate_config(config)
    assert message in str(err.value)
