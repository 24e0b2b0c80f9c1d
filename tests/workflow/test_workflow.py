"""The Snakemake campaign: config errors stop it before any job; the coarse campaign runs and its
files agree with the library (status, KKT, samples)."""
import numpy as np
import pytest
import yaml

from ringdamper.campaign.sampling import make_samples
from ringdamper.io import read_netcdf
from tests.snakemake_run import REPO, failure_tail, run_snakemake


def test_bad_config_stops_before_any_job(tmp_path, small_config):
    bad = dict(small_config, mesh={**small_config["mesh"], "n_r_web": 0})
    path = tmp_path / "bad.yaml"
    path.write_text(yaml.safe_dump(bad))
    run = run_snakemake(tmp_path / "out", path, "-n")
    assert run.returncode != 0
    assert "mesh.n_r_web = 0 is out of range: allowed [1, +inf)" in run.stdout + run.stderr
    assert not (tmp_path / "out").exists()


@pytest.mark.slow
def test_small_campaign_runs_and_agrees_with_the_library(tmp_path, small_config):
    """Every rule of the chain runs (coarse mesh): one training and one validation geometry of the
    design known before any round through to dnnm.nc (which pulls in the default ring), every
    reference ring's static state and figure."""
    out = tmp_path / "results"
    table = make_samples(small_config["sampling"])
    chosen = [table.gid[table.split == split].iloc[0] for split in ("training", "validation")]
    targets = [str(out / "geometry" / gid / "dnnm.nc") for gid in chosen]
    targets += [str(out / "figures" / "static_contact_maps.png"), str(out / "modal" / "resonance.yaml")]
    run = run_snakemake(out, REPO / "tests" / "config_small.yaml", *targets)
    assert run.returncode == 0, failure_tail(run)
    assert not (out / "adaptive").exists()       # no adaptive round: none of these files needs one
    for gid in [g for g in table.gid if (out / "geometry" / g / "static.nc").exists()]:
        ds = read_netcdf(out / "geometry" / gid / "static.nc")
        assert ds.attrs["status"] == 0, ds.attrs["reason"]
        assert np.all(ds.N0 >= 0) and np.all(ds.gap >= 0)
        assert float((ds.N0 * ds.gap).max()) == 0.0        # exact complementarity by contract
        assert ds.attrs["equilibrium_residual"] < 1e-8
        assert ds.N0.attrs["units"] == "N" and "long_name" in ds.gap.attrs
    for gid in chosen:
        dnnm = read_netcdf(out / "geometry" / gid / "dnnm.nc")
        assert dnnm.status.values[0] == 0 and abs(dnnm.zeta.values[0]) < 1e-8  # stuck at small amplitude
        assert dnnm.q_res_z.attrs["units"] == "m"
    resonance = yaml.safe_load((out / "modal" / "resonance.yaml").read_text())
    assert resonance["frequency_hz"] == pytest.approx(27 * resonance["speed_rpm"] / 60, rel=1e-9)
    assert "static contact state" in resonance["contact_state"]


def test_the_tests_of_a_module_share_one_worker(request):
    """Under ``make test`` (``--dist loadgroup``) a test carries its group in its id, which sends the
    tests of a module to one worker (tests/conftest.py). pytest 9.2 ignores the attribute
    pytest-xdist 3.8 writes the group into (docs/testing.md, hence the pytest pin): the tests would
    then be spread over both workers, each building the module's and the session's fixtures."""
    if getattr(request.config.option, "loadgroup", False):  # set on the workers of --dist loadgroup
        assert request.node.nodeid.endswith(f"@{request.module.__name__}"), request.node.nodeid
