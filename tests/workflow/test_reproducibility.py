"""Reproducible to the bit, with provenance: a second run of the small campaign from scratch, on one
core, gives the same arrays as the session's run on two (every NetCDF variable, CSV table and YAML
file); every NetCDF records its provenance; the report is regenerated from a copy of the results
alone, with the charts of the studies run into them."""
import shutil

import pytest
import xarray as xr

from ringdamper.io import provenance
from tests.snakemake_run import REPO, effective_config, failure_tail, run_snakemake
from tests.snakemake_run import SMALL_CONFIG as CONFIG
from tools.compare_results import differences


@pytest.mark.slow
def test_a_run_from_scratch_on_one_core_gives_identical_arrays(small_campaign, tmp_path):
    results = tmp_path / "results"
    run = run_snakemake(results, CONFIG, cores=1, timeout=3600)
    assert run.returncode == 0, run.stderr[-4000:]
    assert differences(results, small_campaign) == []


@pytest.mark.slow
def test_every_netcdf_records_its_provenance(small_campaign):
    """Versions, commit, and the hash of the configuration sections its rule declares: those of its
    stage and of the stages upstream (a reduced model depends on no contact setting, a dNNM on
    both)."""
    config = effective_config(CONFIG)
    files = sorted(small_campaign.rglob("*.nc"))
    assert len(files) > 20
    for path in files:
        with xr.open_dataset(path) as ds:
            attrs = ds.attrs
        assert {"ringdamper_version", "git_commit", "numpy_version", "scipy_version",
                "openturns_version", "config_sections", "config_sha256"} <= set(attrs), path
        sections = attrs["config_sections"].split()
        assert attrs["config_sha256"] == provenance({k: config[k] for k in sections})["config_sha256"], path
        expected = {"static.nc": ("contact", "reduction"), "reduced.nc": ("reduction", "contact"),
                    "dnnm.nc": ("dnnm", "sampling")}.get(path.name)
        if expected is not None:
            present, absent = expected
            assert present in sections and absent not in sections, (path, sections)
        if path.parent.parent.name == "geometry":
            assert len(attrs["kappa"]) == 3, path


@pytest.mark.slow
def test_the_report_is_regenerated_from_the_results_alone(small_campaign, tmp_path):
    """A copy of the results folder (no Snakemake metadata for it) gives the report without running
    a job."""
    results = tmp_path / "results"
    shutil.copytree(small_campaign, results, ignore=shutil.ignore_patterns("report.html"))
    run = run_snakemake(results, CONFIG, "--report", results / "report.html")
    assert run.returncode == 0, failure_tail(run)
    html = (results / "report.html").read_text()
    assert all(p.name in html for p in (results / "figures").glob("*.png"))
    dry = run_snakemake(results, CONFIG, "--dry-run")
    assert "Nothing to be done" in dry.stdout + dry.stderr


@pytest.mark.slow
def test_the_report_shows_the_study_charts_run_into_the_results(small_campaign, tmp_path):
    """A study chart in the results folder (a method-limits chart where its rule writes it) appears in
    the report built with the target ``study_charts`` (as ``make report`` builds it), with its
    caption, and no job runs for it; the campaign's own report, without the chart, shows none."""
    assert "method_limits_" not in (small_campaign / "report.html").read_text()
    results = tmp_path / "results"
    shutil.copytree(small_campaign, results, ignore=shutil.ignore_patterns("report.html"))
    chart = results / "fidelity" / "limits" / "method_limits_stability.png"
    chart.parent.mkdir(parents=True)
    shutil.copyfile(REPO / "docs" / "figures" / "method_limits_stability.png", chart)
    run = run_snakemake(results, CONFIG, "--report", results / "report.html", "all", "study_charts")
    assert run.returncode == 0, failure_tail(run)
    html = (results / "report.html").read_text()
    assert "method_limits_stability.png" in html
    assert "harmonic-balance Jacobian for a Duffing oscillator" in html       # its caption
    assert not (results / "fidelity" / "limits" / "stability.nc").exists()
