"""A run killed in the middle of an adaptive round resumes in that round. Round 1 is run first, to know
its rings; a second run towards the dataset, with the static job of round 1's first ring stalled
(``tests/faults``), is killed with SIGKILL once round 1's second ring has its dnnm.nc. Resumed
(``--unlock``, ``--rerun-incomplete``, without the stall), it recomputes no finished geometry and no
finished round, and ends with the rounds and the dataset of an uninterrupted run."""
from typing import NamedTuple

import pytest
import yaml

from tests.snakemake_run import SMALL_CONFIG as CONFIG
from tests.snakemake_run import failure_tail, fault_environment, kill_when, run_snakemake
from tools.compare_results import file_differences


class Resumed(NamedTuple):
    results: object
    stalled: str      # gid of the round-1 ring stalled, then killed
    at_kill: dict     # path -> mtime (ns) of every geometry, modal and round file at the kill
    finished: set     # the geometries whose dnnm.nc existed at the kill
    after: dict


def _outputs(results) -> dict:
    return {str(p): p.stat().st_mtime_ns for sub in ("geometry", "modal", "adaptive") if (results / sub).exists()
            for p in (results / sub).rglob("*") if p.is_file()}


@pytest.fixture(scope="module")
def resumed(tmp_path_factory) -> Resumed:
    work = tmp_path_factory.mktemp("killed_round")
    results = work / "results"
    first = run_snakemake(results, CONFIG, results / "adaptive" / "round_1.yaml", cores=2, timeout=1800)
    assert first.returncode == 0, first.stderr[-3000:]
    stalled, other = yaml.safe_load((results / "adaptive" / "round_1.yaml").read_text())["chosen"][:2]
    env = fault_environment({"stall_static": [stalled["kappa"]]}, work)
    target = results / "campaign" / "dataset.nc"
    log = results / "logs" / "static" / f"{stalled['gid']}.log"
    done = results / "geometry" / other["gid"] / "dnnm.nc"
    kill_when(results, CONFIG, [target], env,
              lambda: log.exists() and "stalled by the test" in log.read_text() and done.exists(),
              "the stall and the round's other ring")
    at_kill = _outputs(results)
    finished = {p.parent.name for p in (results / "geometry").glob("*/dnnm.nc")}
    assert run_snakemake(results, CONFIG, "--unlock", target).returncode == 0
    run = run_snakemake(results, CONFIG, "--rerun-incomplete", target, cores=2, timeout=1800)
    assert run.returncode == 0, failure_tail(run)
    return Resumed(results, stalled["gid"], at_kill, finished, _outputs(results))


@pytest.mark.slow
def test_a_run_killed_in_a_round_recomputes_no_finished_geometry_or_round(resumed):
    results = resumed.results
    assert resumed.stalled not in resumed.finished and len(resumed.finished) >= 11   # 10 initial + 1 of round 1
    kept = {f: t for f, t in resumed.at_kill.items()
            if any(f.startswith(str(results / "geometry" / gid) + "/") for gid in resumed.finished)
            or f == str(results / "adaptive" / "round_1.yaml")}
    assert {f: resumed.after[f] for f in kept} == kept
    stalled = results / "geometry" / resumed.stalled
    assert all((stalled / name).exists() for name in ("static.nc", "reduced.nc", "dnnm.nc"))
    assert (results / "adaptive" / "round_2.yaml").exists()        # the loop went on from round 1


@pytest.mark.slow
def test_the_resumed_run_ends_with_the_rounds_and_dataset_of_an_uninterrupted_one(resumed, small_campaign):
    rounds = sorted(p.name for p in (small_campaign / "adaptive").glob("round_*.yaml"))
    assert sorted(p.name for p in (resumed.results / "adaptive").glob("round_*.yaml")) == rounds
    for rel in [f"adaptive/{name}" for name in rounds] + ["campaign/dataset.nc", "samples.csv"]:
        assert file_differences(resumed.results / rel, small_campaign / rel) == [], rel
