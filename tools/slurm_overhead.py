"""The cost of running the workflow's jobs through SLURM: for the cluster jobs one Snakemake run
submitted, their time in SLURM (allocation to completion, from slurmctld's log) against the time of
the rules they ran (the ``s`` column of the rules' benchmark files), and the difference per cluster
job: starting the job, a Snakemake process that parses the workflow again, and the status checks.

    python -m tools.slurm_overhead SLURMCTLD_LOG SNAKEMAKE_LOG
"""
import re
import sys
from datetime import datetime
from pathlib import Path

import pandas as pd

SUBMITTED = re.compile(r"submitted with SLURM jobid (\d+)")
# a job starts on "sched: Allocate JobId=N" (main scheduler) or "sched/backfill: _start_job: Started JobId=N"
EVENT = re.compile(r"^\[([^\]]+)\] (sched: Allocate|sched/backfill: _start_job: Started|_job_complete:) "
                   r"JobId=(\d+)( done)?")


def slurm_elapsed(ctld_log: str, job_ids: set[str]) -> dict[str, float]:
    """Seconds from allocation to completion of each job of ``job_ids`` that completed."""
    start, elapsed = {}, {}
    for line in Path(ctld_log).read_text().splitlines():
        event = EVENT.match(line)
        if event and event.group(3) in job_ids:
            when, kind, job, done = datetime.fromisoformat(event.group(1)), *event.group(2, 3, 4)
            if kind.startswith("sched"):
                start[job] = when
            elif done and job in start:
                elapsed[job] = (when - start[job]).total_seconds()
    return elapsed


def cluster_benchmarks(snakemake_log: str) -> list[str]:
    """The benchmark files of the rules the run sent to the cluster (not its local rules)."""
    files, local = [], False
    for line in Path(snakemake_log).read_text().splitlines():
        if re.match(r"^\s*(local)?rule \w+:", line):
            local = line.strip().startswith("localrule")
        elif (found := re.match(r"^\s*benchmark: (\S+)", line)) and not local:
            files.append(found.group(1))
    return sorted(set(files))


def main(ctld_log: str, snakemake_log: str) -> str:
    job_ids = set(SUBMITTED.findall(Path(snakemake_log).read_text()))
    elapsed = slurm_elapsed(ctld_log, job_ids)
    rules = sum(float(pd.read_csv(f, sep="\t")["s"].iloc[0]) for f in cluster_benchmarks(snakemake_log))
    in_slurm = sum(elapsed.values())
    return (f"{len(elapsed)} cluster jobs: {in_slurm:.0f} s in SLURM, {rules:.0f} s in their rules' "
            f"benchmarks, {(in_slurm - rules) / max(len(elapsed), 1):.1f} s of overhead per cluster job")


if __name__ == "__main__":
    print(main(*sys.argv[1:3]))
