"""The adaptive rounds' failure rules through Snakemake, on a synthetic results tree of the test
configuration: analytic dnnm.nc files stand in for the initial rings' chains, round 1's record and
rings are written by the test, and only round 2 may run (``--allowed-rules``). A failed ring of
round 1 is excluded and named, and the loop goes on; if every ring of round 1 failed, round 2 stops
the campaign with an error naming them."""
import numpy as np
import pytest
import yaml

from ringdamper.campaign.adaptive.rounds import round_models, training_dataset
from ringdamper.campaign.sampling import make_samples
from ringdamper.io import write_netcdf
from ringdamper.nonlinear.stage import amplitude_grid, failed_dnnm
from tests.snakemake_run import SMALL_CONFIG, failure_tail, run_snakemake

from .synthetic import dnnm_dataset, write_campaign

ROUND_1 = [{"gid": "a01_000", "kappa": [0.5, 0.5, -0.5]}, {"gid": "a01_001", "kappa": [-0.5, -0.5, 0.5]}]


def _tree(out, small_config, failed):
    """Initial rings and round 1 (its rings ``failed`` failed; its record and the models it fitted on the
    initial rings) of a synthetic campaign under ``out``."""
    samples = make_samples(small_config["sampling"])
    alpha = amplitude_grid(small_config["dnnm"])
    paths = write_campaign(out, samples[samples.split == "training"], alpha)
    write_netcdf(round_models(*training_dataset(samples, [], paths), small_config).kriging,
                 out / "adaptive" / "round_1_kriging.nc")
    for ring in ROUND_1:
        ds = (failed_dnnm(small_config, ring["kappa"], "RuntimeError: static solve failed", 3)
              if ring["gid"] in failed else dnnm_dataset(ring["kappa"], alpha))
        write_netcdf(ds, out / "geometry" / ring["gid"] / "dnnm.nc")
    record = {"round": 1, "n_computed": 10, "n_usable": 10, "excluded": [], "estimates": {}, "ratios": {},
              "stop": False, "reason": None, "optimum_changes": [],
              "optimum": {"kappa": [0.4, -0.3, 0.2], "zeta_max": 3e-3, "zeta_max_std": 1e-5},
              "chosen": [dict(ring, score=1.0, explore=1.0, exploit=0.0) for ring in ROUND_1]}
    (out / "adaptive" / "round_1.yaml").write_text(yaml.safe_dump(record))


@pytest.mark.slow
def test_a_failed_ring_is_excluded_and_named_and_the_loop_goes_on(tmp_path, small_config):
    out = tmp_path / "results"
    _tree(out, small_config, failed={"a01_000"})
    run = run_snakemake(out, SMALL_CONFIG, out / "adaptive" / "round_2.yaml", "--allowed-rules", "adaptive_round")
    assert run.returncode == 0, failure_tail(run)
    assert not (out / "logs" / "dnnm").exists()     # the synthetic rings were not recomputed
    record = yaml.safe_load((out / "adaptive" / "round_2.yaml").read_text())
    assert record["excluded"] == ["a01_000"] and record["n_computed"] == 12 and record["n_usable"] == 11
    assert not record["stop"] and len(record["chosen"]) == small_config["sampling"]["adaptive"]["batch"]
    assert np.isfinite(list(record["estimates"]["variance"].values())).all()
    assert "a01_000" in (out / "logs" / "adaptive" / "round_2.log").read_text()


@pytest.mark.slow
def test_a_round_whose_rings_all_failed_stops_the_campaign_naming_them(tmp_path, small_config):
    out = tmp_path / "results"
    _tree(out, small_config, failed={"a01_000", "a01_001"})
    run = run_snakemake(out, SMALL_CONFIG, out / "adaptive" / "round_2.yaml", "--allowed-rules", "adaptive_round")
    assert run.returncode != 0
    assert not (out / "adaptive" / "round_2.yaml").exists()
    log = (out / "logs" / "adaptive" / "round_2.log").read_text()
    assert "every ring of round 1 failed: a01_000 (RuntimeError: static solve failed); a01_001" in log
