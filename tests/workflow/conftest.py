"""The whole small campaign (tests/config_small.yaml), run once per session on 2 cores and shared
by the workflow tests that read it or compare against it."""
import pytest

from tests.snakemake_run import SMALL_CONFIG as CONFIG
from tests.snakemake_run import run_snakemake


@pytest.fixture(scope="session")
def small_campaign(tmp_path_factory):
    """Results folder of the whole small campaign, then the report (which must not recompute
    anything)."""
    results = tmp_path_factory.mktemp("campaign") / "results"
    run = run_snakemake(results, CONFIG, cores=2, timeout=3600)
    assert run.returncode == 0, run.stderr[-4000:]
    run = run_snakemake(results, CONFIG, "--report", results / "report.html", cores=2)
    assert run.returncode == 0, run.stderr[-4000:]
    dry = run_snakemake(results, CONFIG, "--dry-run", cores=2)
    assert "Nothing to be done" in dry.stdout + dry.stderr
    return results
