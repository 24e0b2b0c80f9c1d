"""A configuration edit reruns exactly the jobs whose outputs depend on it. Each rule declares its
configuration sections as ``params.config`` (workflow/rules/common.smk), and Snakemake's params
trigger compares them with those recorded when the outputs were made: a dry run on the finished small
campaign, with one value edited, lists the jobs of the stage that reads it and everything downstream,
and nothing upstream or beside it. The adaptive design (its rounds, samples.csv) is downstream of every
dNNM: the rounds choose the rings from them."""
import copy

import pytest
import yaml

from tests.snakemake_run import SMALL_CONFIG, dry_run_jobs, effective_config


def _edited(tmp_path, edit) -> str:
    """The small configuration with ``edit`` applied, written with its keys sorted (an order of its own,
    which alone reruns nothing)."""
    config = copy.deepcopy(yaml.safe_load(SMALL_CONFIG.read_text()))
    edit(config)
    path = tmp_path / "edited.yaml"
    path.write_text(yaml.safe_dump(config, sort_keys=True))
    return path


@pytest.fixture(scope="module")
def every_job(small_campaign):
    """rule -> job count of the whole campaign (a forced dry run)."""
    return dry_run_jobs(small_campaign, SMALL_CONFIG, "--forceall")


def _scale(section, key, factor):
    def edit(config):
        config[section][key] *= factor
    return edit


@pytest.mark.slow
def test_a_friction_edit_reruns_static_and_dnnm_and_everything_downstream(small_campaign, every_job, tmp_path):
    jobs = dry_run_jobs(small_campaign, _edited(tmp_path, _scale("contact", "friction_coefficient", 1.5)))
    upstream_or_beside = {"reduced"}   # samples.csv is downstream: the adaptive rounds read the dNNMs
    assert {rule: n for rule, n in jobs.items() if rule != "reduced"} == {
        rule: n for rule, n in every_job.items() if rule not in upstream_or_beside}
    assert jobs["static"] == jobs["dnnm"] == every_job["dnnm"]       # every geometry's static and dNNM
    assert jobs["reduced"] == 1    # the optimum's only: its kappa comes from the refitted surrogates


@pytest.mark.slow
def test_a_dnnm_edit_leaves_the_static_reduction_and_modal_stages(small_campaign, every_job, tmp_path):
    jobs = dry_run_jobs(small_campaign, _edited(tmp_path, _scale("dnnm", "n_time_samples", 2)))
    assert {"stuck_default", "dnnm", "aggregate", "kriging", "frf_curve"} <= set(jobs)
    assert not set(jobs) & {"modal", "static_maps"}
    assert {"adaptive_round", "samples"} <= set(jobs)      # the adaptive design is chosen from the dNNMs
    assert jobs["static"] == jobs["reduced"] == 1   # the optimum's only, downstream of the surrogates
    assert jobs["dnnm"] == every_job["dnnm"]


@pytest.mark.slow
def test_a_forced_response_edit_reruns_only_the_forced_responses_and_what_reads_them(small_campaign, tmp_path):
    def widen(config):
        config["frf"]["frequency_band"] = [0.98, 1.02]
    jobs = dry_run_jobs(small_campaign, _edited(tmp_path, widen))
    assert set(jobs) == {"frf_levels", "frf_curve", "table3", "optimum_figures", "paper_comparison",
                         "adaptive_report", "all"}


@pytest.mark.slow
def test_a_studies_edit_reruns_no_campaign_job(small_campaign, tmp_path):
    def studies(config):
        config["studies"] = copy.deepcopy(effective_config(SMALL_CONFIG)["studies"])
        config["studies"]["hub_calibration"]["xtol"] *= 2
    assert dry_run_jobs(small_campaign, _edited(tmp_path, studies)) == {}
