"""Reproducible to the bit, with provenance: a second run of the small campaign from scratch, on one
core, gives the same arrays as the session's run on two (every NetCDF variable, CSV table and YAML
file); every NetCDF records its provenance; the report is regenerated from a copy of the results
alone."""
import shutil

import pytest
import xarray as xr

from ringdamper.io import CONFIG_SECTIONS
from tests.snakemake_run import SMALL_CONFIG as CONFIG, run_snakemake
from tools.compare_results import differences


@pytest.mark.slow
def test_a_run_from_scratch_on_one_core_gives_identical_arrays(small_campaign, tmp_path):
    results = tmp_path / "results"
    run = run_snakemake(results, CONFIG, cores=1, timeout=3600)
    assert run.returncode == 0, run.stderr[-4000:]
    assert differences(results, small_campaign) == []


@pytest.mark.slow
def test_every_netcdf_records_its_provenance(small_campaign):
    files = sorted(small_campaign.rglob("*.nc"))
    assert len(files) > 20
    for path in files:
        with xr.open_dataset(path) as ds:
            attrs = ds.attrs
        assert {"ringdamper_version", "git_commit", "numpy_version", "scipy_version",
                "openturns_version", "config_sections", "config_sha256"} <= set(attrs), path
        assert attrs["config_sections"].split() in [list(v) for v in CONFIG_SECTIONS.values()], path
        assert len(attrs["config_sha256"]) == 64
        if path.parent.parent.name == "geometry":
            assert len(attrs["kappa"]) == 3, path


@pytest.mark.slow
def test_the_report_is_regenerated_from_the_results_alone(small_campaign, tmp_path):
    """A copy of the results folder (no Snakemake metadata for it) gives the report without running
    a job."""
    results = tmp_path / "results"
    shutil.copytree(small_campaign, results, ignore=shutil.ignore_patterns("report.html"))
    run = run_snakemake(results, CONFIG, "--report", results / "report.html")
    assert run.returncode == 0, run.stderr[-3000:]
    html = (results / "report.html").read_text()
    assert all(p.name in html for p in (results / "figures").glob("*.png"))
    dry = run_snakemake(results, CONFIG, "--dry-run")
    assert "Nothing to be done" in dry.stdout + dry.stderr
