"""Kills and bad files lose nothing. A run of three geometries' chains killed with SIGKILL midway
(Snakemake and its jobs, as a crash would) and resumed (``--unlock``, ``--rerun-incomplete``)
recomputes only the jobs that were running or had not started, and ends with the arrays of an
uninterrupted run. A corrupt reduced.nc fails its dnnm job naming the file, and once the file is
repaired, even with its old timestamp, a rerun recomputes dnnm.nc."""
import os
import re
import shutil
import signal
import subprocess
import time

import pytest

from ringdamper.campaign.sampling import make_samples
from ringdamper.io import read_netcdf
from tests.snakemake_run import SMALL_CONFIG as CONFIG, run_snakemake, snakemake_command
from tools.compare_results import file_differences

STAGES = ("static.nc", "reduced.nc", "dnnm.nc")


def _gids(small_config):
    """The default ring and two other training geometries."""
    table = make_samples(small_config["sampling"])
    default = table.gid[(table[["kappa1", "kappa2", "kappa3"]] == 0.0).all(axis=1)].iloc[0]
    others = [g for g in table.gid[table.split == "training"] if g != default][:2]
    return [default, *others]


def _outputs(results) -> dict:
    """mtime (ns) of every output file of the geometries' chains and the modal stage."""
    return {str(p): p.stat().st_mtime_ns for sub in ("geometry", "modal") if (results / sub).exists()
            for p in (results / sub).rglob("*") if p.is_file()}


def _incomplete(dry_run: str) -> list[list[str]]:
    """Output files of each job that a dry run reruns because its outputs are incomplete."""
    jobs = []
    for block in re.split(r"\n\s*\n", dry_run):
        if "reason: Incomplete output files" in block:
            outputs = re.search(r"output: (.*)", block).group(1)
            jobs.append([f.strip() for f in outputs.split(",")])
    return jobs


@pytest.fixture(scope="module")
def resumed(tmp_path_factory, small_config):
    """Kill a run once four of its jobs have finished, then resume it: (results, gids, mtimes at the
    kill, incomplete jobs, mtimes after the resume, resume output)."""
    results = tmp_path_factory.mktemp("killed") / "results"
    gids = _gids(small_config)
    targets = [results / "geometry" / gid / "dnnm.nc" for gid in gids]
    proc = subprocess.Popen(snakemake_command(results, CONFIG, *targets, cores=2), start_new_session=True,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    deadline = time.monotonic() + 600
    while len(list((results / "benchmarks").rglob("*.tsv"))) < 4 and proc.poll() is None:
        assert time.monotonic() < deadline, "the run did not reach four jobs in 600 s"
        time.sleep(0.05)
    assert proc.poll() is None, "the run ended before it could be killed"
    os.killpg(proc.pid, signal.SIGKILL)
    proc.wait()
    at_kill = _outputs(results)
    dry = run_snakemake(results, CONFIG, "--dry-run", "--rerun-incomplete", *targets)
    if "cannot be locked" in dry.stdout + dry.stderr:
        assert run_snakemake(results, CONFIG, "--unlock", *targets).returncode == 0
        dry = run_snakemake(results, CONFIG, "--dry-run", "--rerun-incomplete", *targets)
    assert dry.returncode == 0, dry.stderr[-3000:]
    run = run_snakemake(results, CONFIG, "--rerun-incomplete", *targets, cores=2)
    assert run.returncode == 0, run.stderr[-3000:]
    return results, gids, at_kill, _incomplete(dry.stdout), _outputs(results), run.stdout + run.stderr


@pytest.mark.slow
def test_a_killed_run_resumes_recomputing_only_what_was_unfinished(resumed):
    results, gids, at_kill, incomplete, after, log = resumed
    assert len(incomplete) <= 2                    # at most the jobs running on the 2 cores
    unfinished = {f for job in incomplete for f in job}
    kept = {f for f in at_kill if f not in unfinished}
    assert kept, "nothing had finished at the kill"
    assert {f: after[f] for f in kept} == {f: at_kill[f] for f in kept}   # not recomputed
    recomputed = {f for f in after if at_kill.get(f) != after[f]}
    assert recomputed and recomputed.isdisjoint(kept)
    for gid in gids:
        assert all((results / "geometry" / gid / name).exists() for name in STAGES)


@pytest.mark.slow
def test_a_resumed_run_ends_with_the_arrays_of_an_uninterrupted_one(resumed, small_campaign):
    results, gids = resumed[:2]
    for rel in [f"geometry/{gid}/{name}" for gid in gids for name in STAGES] + ["modal/nd_diagram.nc"]:
        assert file_differences(results / rel, small_campaign / rel) == [], rel


@pytest.mark.slow
def test_a_corrupt_input_fails_its_job_naming_it_and_a_rerun_after_repair_recomputes(resumed, tmp_path):
    """The repaired reduced.nc keeps the timestamp it had before the corruption (a restored backup):
    dnnm.nc is recomputed all the same, because the failed job left no output behind."""
    results, gids = resumed[:2]
    work = tmp_path / "results"
    shutil.copytree(results, work)
    reduced, dnnm = (work / "geometry" / gids[1] / name for name in ("reduced.nc", "dnnm.nc"))
    good, stamp = reduced.read_bytes(), reduced.stat()
    reduced.write_bytes(good[: len(good) // 2])
    run = run_snakemake(work, CONFIG, dnnm)
    assert run.returncode != 0
    log = (work / "logs" / "dnnm" / f"{gids[1]}.log").read_text()
    assert f"{reduced}: truncated or not a NetCDF file" in log
    assert not dnnm.exists()
    reduced.write_bytes(good)
    os.utime(reduced, ns=(stamp.st_atime_ns, stamp.st_mtime_ns))
    run = run_snakemake(work, CONFIG, dnnm)
    assert run.returncode == 0, run.stderr[-3000:]
    assert read_netcdf(dnnm, "dnnm").status.values[0] == 0
    assert file_differences(dnnm, results / "geometry" / gids[1] / "dnnm.nc") == []
