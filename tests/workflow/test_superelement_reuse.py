"""The fixed part's super-element is built once per campaign: with ``substructure.enabled`` a first
ring's static and reduced jobs build it, a second ring's jobs read it without rebuilding it, an
edit of the blisk (material, speed) rebuilds it, an edit of the ring's thickness or clearance does
not (the rule's params are ``superelement.blisk_config``). On the coarse test campaign."""
import copy

import pytest
import yaml

from ringdamper.campaign.sampling import make_samples
from tests.snakemake_run import SMALL_CONFIG, dry_run_jobs, effective_config, run_snakemake


def _write(config: dict, path) -> str:
    path.write_text(yaml.safe_dump(config, sort_keys=True))
    return path


@pytest.fixture(scope="module")
def campaign(tmp_path_factory):
    """(results folder, substructured configuration, two gids) after the first ring's jobs ran."""
    folder = tmp_path_factory.mktemp("superelement")
    config = copy.deepcopy(yaml.safe_load(SMALL_CONFIG.read_text()))
    config["substructure"] = {"enabled": True, "n_modes": 20}
    gids = list(make_samples(effective_config(SMALL_CONFIG)["sampling"])["gid"][:2])
    results = folder / "results"
    path = _write(config, folder / "substructured.yaml")
    run = run_snakemake(results, path, *_targets(results, gids[0]))
    assert run.returncode == 0, run.stderr[-3000:]
    return results, config, gids, folder


def _targets(results, gid):
    return [results / "geometry" / gid / name for name in ("static.nc", "reduced.nc")]


@pytest.mark.slow
def test_a_second_ring_reads_the_super_element_without_rebuilding_it(campaign):
    results, config, gids, folder = campaign
    assert (results / "superelement" / "fixed_part.npz").is_file()
    jobs = dry_run_jobs(results, _write(config, folder / "same.yaml"), *_targets(results, gids[1]))
    assert jobs == {"static": 1, "reduced": 1}


@pytest.mark.slow
@pytest.mark.parametrize("section, key, value, rebuilt", [
    ("material", "density", 4500.0, True),
    ("operation", "speed_rpm", 2500.0, True),
    ("ring", "thickness", 0.0042, False),
    ("ring", "radial_clearance", 1.0e-5, False),
    ("mesh", "contact_pairs", {"placement": "grid", "n_theta": 9, "n_axial": 4}, False),
])
def test_blisk_edits_rebuild_it_and_ring_edits_do_not(campaign, section, key, value, rebuilt):
    results, config, gids, folder = campaign
    edited = copy.deepcopy(config)
    target = edited["geometry"]["ring"] if section == "ring" else edited[section]
    target[key] = value
    jobs = dry_run_jobs(results, _write(edited, folder / f"{key}.yaml"), *_targets(results, gids[0]))
    assert ("superelement" in jobs) == rebuilt, jobs
    assert jobs.get("reduced") == 1 and jobs.get("static") == 1    # the ring's own jobs rerun
