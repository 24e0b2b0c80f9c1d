"""Kills and bad files lose nothing. A run of three geometries' chains is killed with SIGKILL
(Snakemake and its jobs, as a crash would) at a known point: one geometry's static job, stalled by a
test-side fault (``tests/faults``), has written its two VTU files and not yet static.nc, while
the other core has gone on with the other chains. Resumed (``--unlock``, ``--rerun-incomplete``, without
the stall), the run recomputes only the jobs that were running or had not
started, that half-done job among them, and ends with the arrays of an uninterrupted run. A corrupt
reduced.nc fails its dnnm job naming the file, and once the file is repaired, even with its old
timestamp, a rerun recomputes dnnm.nc."""
import os
import re
import shutil
from typing import NamedTuple

import pytest

from ringdamper.campaign.sampling import make_samples
from ringdamper.io import InputFileError, read_netcdf
from tests.snakemake_run import SMALL_CONFIG as CONFIG
from tests.snakemake_run import fault_environment, kill_when, run_snakemake
from tools.compare_results import file_differences

STAGES = ("static.nc", "reduced.nc", "dnnm.nc")


def _gids(small_config):
    """The default ring and two other training geometries."""
    table = make_samples(small_config["sampling"])
    default = table.gid[(table[["kappa1", "kappa2", "kappa3"]] == 0.0).all(axis=1)].iloc[0]
    others = [g for g in table.gid[table.split == "training"] if g != default][:2]
    return [default, *others]


def _outputs(results) -> dict:
    """mtime (ns) of every output file of the geometries' chains and the modal stage; not the temporary
    of a writer the kill interrupted (:func:`_temporaries`)."""
    return {str(p): p.stat().st_mtime_ns for sub in ("geometry", "modal") if (results / sub).exists()
            for p in (results / sub).rglob("*") if p.is_file() and not _is_temporary(p)}


def _is_temporary(path) -> bool:
    """A writer's temporary (``.{stem}.{pid}.part{suffix}``, :func:`ringdamper.io.written_whole`)."""
    return path.name.startswith(".") and ".part" in path.suffixes


def _temporaries(results) -> list[str]:
    """The writers' temporaries under ``results``: a process killed while writing leaves one, which the
    next write of its file removes."""
    return [str(p) for p in results.rglob(".*") if p.is_file() and _is_temporary(p)]


def _scheduled_jobs(dry_run: str) -> list[tuple[list[str], str]]:
    """(output paths, reason) of every job a dry run would run (Snakemake prints one block per job,
    opened by ``rule <name>:``)."""
    jobs = []
    for block in re.split(r"^\s*(?:local)?rule \w+:\s*$", dry_run, flags=re.MULTILINE)[1:]:
        outputs = re.search(r"^\s*output: (.*)$", block, flags=re.MULTILINE)
        reason = re.search(r"^\s*reason: (.*)$", block, flags=re.MULTILINE)
        if outputs:
            jobs.append(([f.strip() for f in outputs.group(1).split(",")], reason.group(1) if reason else ""))
    return jobs


# Why a resumed run may run a job: it was running at the kill (Snakemake 9 reports the incomplete
# outputs it reruns under --rerun-incomplete, on by default in the profile, as "Forced execution";
# older versions as "Incomplete output files"), it had not started or had not written all its
# outputs, or it lies downstream of such a job. Anything else (timestamps, code, parameters) would
# be a needless recomputation.
RESUME_REASONS = ("Forced execution", "Incomplete output files", "Missing output files",
                  "Input files updated by another job")


def _belongs(path: str, outputs: list[str]) -> bool:
    """Whether ``path`` is one of a job's outputs or lies in one of its output directories."""
    return any(path == out or path.startswith(out.rstrip("/") + "/") for out in outputs)


class Resumed(NamedTuple):
    results: object         # the results folder
    gids: list              # the three geometries
    stalled: str            # the geometry whose static job was stalled, then killed
    at_kill: dict           # path -> mtime (ns) of every output at the kill
    unreadable: list        # the NetCDF files at the kill that could not be read
    scheduled: list         # (outputs, reason) of every job the resume runs
    after: dict             # path -> mtime (ns) of every output after the resume


def _unreadable(paths) -> list[str]:
    """The NetCDF files of ``paths`` that :func:`read_netcdf` cannot read."""
    bad = []
    for path in (p for p in paths if p.endswith(".nc")):
        try:
            read_netcdf(path)
        except InputFileError:
            bad.append(path)
    return bad


@pytest.fixture(scope="module")
def resumed(tmp_path_factory, small_config) -> Resumed:
    """Kill a run once its stalled job waits and four jobs have finished, then resume it."""
    work = tmp_path_factory.mktemp("killed")
    results = work / "results"
    gids = _gids(small_config)
    stalled = gids[1]
    kappa = make_samples(small_config["sampling"]).set_index("gid").loc[stalled, ["kappa1", "kappa2", "kappa3"]]
    env = fault_environment({"stall_static": [kappa.tolist()]}, work)
    targets = [results / "geometry" / gid / "dnnm.nc" for gid in gids]
    log = results / "logs" / "static" / f"{stalled}.log"
    kill_when(results, CONFIG, targets, env,
              lambda: (log.exists() and "stalled by the test" in log.read_text()
                       and len(list((results / "benchmarks").rglob("*.tsv"))) >= 4),
              "the stall and four finished jobs")
    at_kill = _outputs(results)
    unreadable = _unreadable(at_kill)
    assert run_snakemake(results, CONFIG, "--unlock", *targets).returncode == 0
    dry = run_snakemake(results, CONFIG, "--dry-run", "--rerun-incomplete", *targets)
    assert dry.returncode == 0, dry.stderr[-3000:]
    run = run_snakemake(results, CONFIG, "--rerun-incomplete", *targets, cores=2)
    assert run.returncode == 0, run.stderr[-3000:]
    return Resumed(results, gids, stalled, at_kill, unreadable, _scheduled_jobs(dry.stdout + dry.stderr),
                   _outputs(results))


@pytest.mark.slow
def test_a_killed_run_resumes_recomputing_only_what_was_unfinished(resumed):
    """The resume reruns the jobs that were running at the kill (at most one per core: the only
    rerun jobs with outputs on disk), those that had not started and those downstream of them, for
    no other reason; every other file keeps its timestamp."""
    results, gids, at_kill, scheduled, after = (resumed.results, resumed.gids, resumed.at_kill,
                                                 resumed.scheduled, resumed.after)
    for outputs, reason in scheduled:
        assert all(part.split(":")[0].strip() in RESUME_REASONS for part in reason.split(";")), (outputs, reason)
    started = [outputs for outputs, _ in scheduled if any(_belongs(f, outputs) for f in at_kill)]
    assert len(started) <= 2, started
    kept = {f for f in at_kill if not any(_belongs(f, outputs) for outputs, _ in scheduled)}
    assert kept, "nothing had finished at the kill"
    assert {f: after[f] for f in kept} == {f: at_kill[f] for f in kept}   # not recomputed
    recomputed = {f for f in after if at_kill.get(f) != after[f]}
    assert recomputed and recomputed.isdisjoint(kept)
    for gid in gids:
        assert all((results / "geometry" / gid / name).exists() for name in STAGES)


@pytest.mark.slow
def test_the_job_killed_with_part_of_its_outputs_written_is_recomputed_whole(resumed):
    """The stalled static job had written static.vtu and mesh.vtu, not static.nc: the resume reruns it
    as incomplete and rewrites both files. No NetCDF at the kill was half-written (a job killed while
    writing one leaves none: io.written_whole)."""
    folder = resumed.results / "geometry" / resumed.stalled
    written = {str(folder / name) for name in ("static.vtu", "mesh.vtu")}
    assert written <= set(resumed.at_kill) and str(folder / "static.nc") not in resumed.at_kill
    (_, reason), = [job for job in resumed.scheduled if str(folder / "static.nc") in job[0]]
    assert reason.split(":")[0] in ("Forced execution", "Incomplete output files"), reason
    assert all(resumed.after[f] != resumed.at_kill[f] for f in written)
    assert resumed.unreadable == []
    assert not _temporaries(resumed.results)         # a killed write's temporary is removed by its rerun


@pytest.mark.slow
def test_a_resumed_run_ends_with_the_arrays_of_an_uninterrupted_one(resumed, small_campaign):
    results, gids = resumed.results, resumed.gids
    for rel in [f"geometry/{gid}/{name}" for gid in gids for name in STAGES] + ["modal/nd_diagram.nc"]:
        assert file_differences(results / rel, small_campaign / rel) == [], rel


@pytest.mark.slow
def test_a_corrupt_input_fails_its_job_naming_it_and_a_rerun_after_repair_recomputes(resumed, tmp_path):
    """The repaired reduced.nc keeps the timestamp it had before the corruption (a restored backup):
    dnnm.nc is recomputed all the same, because the failed job left no output behind."""
    results, gids = resumed.results, resumed.gids
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
