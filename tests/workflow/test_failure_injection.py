"""A geometry whose chain fails loses nothing else. A test-side fault (``tests/faults``) makes one
training geometry's static solve raise after meshing; the campaign still ends (return code 0), every
adaptive round excludes the geometry and the loop goes on, the geometry's static.nc and dnnm.nc have a
solved file's variables, all NaN, with status 99 and the reason, the dataset keeps it flagged, and the
Kriging fits exclude it with a warning naming it."""
import numpy as np
import pandas as pd
import pytest
import yaml

from ringdamper.campaign.sampling import make_samples
from ringdamper.io import read_netcdf
from tests.snakemake_run import SMALL_CONFIG, failure_tail, fault_environment, run_snakemake


@pytest.mark.slow
def test_an_injected_static_failure_is_flagged_and_excluded_and_the_campaign_ends(tmp_path, small_config):
    table = make_samples(small_config["sampling"])
    kappa = table[["kappa1", "kappa2", "kappa3"]].to_numpy()
    training = table.index[(table.split == "training") & np.any(kappa != 0, axis=1)]
    failed, healthy = table.gid[training[-1]], table.gid[training[0]]
    env = fault_environment({"static": [kappa[training[-1]].tolist()]}, tmp_path)
    out = tmp_path / "results"

    run = run_snakemake(out, SMALL_CONFIG, out / "surrogate" / "kriging.nc", cores=2, timeout=1800, env=env)
    assert run.returncode == 0, failure_tail(run)

    for name, kind in (("static.nc", "static"), ("dnnm.nc", "dnnm")):
        bad = read_netcdf(out / "geometry" / failed / name, kind)
        good = read_netcdf(out / "geometry" / healthy / name, kind)
        assert set(bad.data_vars) == set(good.data_vars), name
        assert "fault injected" in bad.attrs["reason"], name
        for var in (v for v in bad.data_vars if v not in ("status", "in_contact")):
            assert np.all(np.isnan(bad[var].values)), (name, var)
    assert read_netcdf(out / "geometry" / failed / "static.nc", "static").attrs["status"] == 99
    assert np.all(read_netcdf(out / "geometry" / failed / "dnnm.nc", "dnnm")["status"].values == 99)

    dataset = read_netcdf(out / "campaign" / "dataset.nc")
    assert failed in dataset.geometry.values.tolist()
    assert np.all(dataset["status"].sel(geometry=failed).values == 99)
    n_amplitudes = small_config["dnnm"]["n_amplitudes"]                     # its points, counted
    assert f"{n_amplitudes} chain failed" in (out / "logs" / "aggregate.log").read_text()
    warning = f"WARNING ringdamper.campaign.dataset: geometry {failed} (training) excluded"
    assert warning in (out / "logs" / "kriging.log").read_text()
    kriging = read_netcdf(out / "surrogate" / "kriging.nc")
    samples = pd.read_csv(out / "samples.csv")
    n_training = int((samples.split == "training").sum())
    assert int(kriging["n_training"].max()) == n_training - 1
    rounds = sorted((out / "adaptive").glob("round_*.yaml"))                # the adaptive loop went on
    assert len(rounds) >= 2
    for path in rounds:
        record = yaml.safe_load(path.read_text())
        assert record["excluded"] == [failed] and record["n_usable"] == record["n_computed"] - 1, path
