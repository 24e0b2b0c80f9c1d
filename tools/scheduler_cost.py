"""The scheduler's own CPU cost: run ``snakemake ARGS`` in this process and print, at exit, the CPU
seconds of the Snakemake process itself (getrusage RUSAGE_SELF) against those of the jobs it ran
(RUSAGE_CHILDREN: every job process it waited for), the wall time, and the scheduler's share.

    python tools/scheduler_cost.py --cores 2 --configfile tests/config_small.yaml
"""
import atexit
import json
import resource
import sys
import time

START = time.perf_counter()


def report() -> None:
    own, jobs = (resource.getrusage(who) for who in (resource.RUSAGE_SELF, resource.RUSAGE_CHILDREN))
    own_s, jobs_s = own.ru_utime + own.ru_stime, jobs.ru_utime + jobs.ru_stime
    print(json.dumps({"wall_s": round(time.perf_counter() - START, 2), "scheduler_cpu_s": round(own_s, 2),
                      "jobs_cpu_s": round(jobs_s, 2),
                      "scheduler_share": round(own_s / max(own_s + jobs_s, 1e-9), 4)}), file=sys.stderr)


atexit.register(report)
from snakemake.cli import main  # noqa: E402 (the clock starts before Snakemake's import)

main(sys.argv[1:])
