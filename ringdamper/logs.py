"""The log of a rule script: the library's ``logging`` records and the interpreter's stderr go to the
rule's log file, so that warnings, tracebacks and the script's own records land in one place; and the
script's CPU time goes, when it exits, to a record beside the log (:func:`cpu_record`).

Snakemake's benchmark files give a job's wall time exactly but its CPU time only as a sample: it polls
the job every 0.5 s for 30 s, then every 30 s, and keeps the last poll, so a job of 41 s wall was
recorded with 14 s of CPU. The record here is the process' own count at exit (``getrusage``: user and
system time of the script and of the worker processes it waited for), which is exact.
"""
from __future__ import annotations

import atexit
import json
import logging
import resource
import sys
from pathlib import Path


def to_file(path) -> logging.Logger:
    """Send stderr and INFO and above of every logger to ``path`` (overwritten), and write the
    script's CPU time to :func:`cpu_record` of ``path`` when it exits; return the root logger, for the
    script's own records."""
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    sys.stderr = open(path, "w", buffering=1)
    handler = logging.StreamHandler(sys.stderr)
    handler.setFormatter(logging.Formatter("%(asctime)s %(levelname)s %(name)s: %(message)s"))
    root = logging.getLogger()
    root.handlers[:] = [handler]
    root.setLevel(logging.INFO)
    atexit.register(write_cpu_record, cpu_record(path))
    return root


def cpu_record(log_path) -> Path:
    """The CPU-time record of the job whose log is ``log_path``: the same path, suffix ``.cpu.json``."""
    return Path(log_path).with_suffix(".cpu.json")


def write_cpu_record(path) -> None:
    """Write the CPU seconds this process and its waited-for children have used so far to ``path``:
    ``{"cpu_s": total, "user_s", "system_s", "children_cpu_s"}``."""
    own = resource.getrusage(resource.RUSAGE_SELF)
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    children_s = children.ru_utime + children.ru_stime
    Path(path).write_text(json.dumps({"cpu_s": own.ru_utime + own.ru_stime + children_s, "user_s": own.ru_utime,
                                      "system_s": own.ru_stime, "children_cpu_s": children_s}) + "\n")


def read_cpu_seconds(path) -> float | None:
    """The ``cpu_s`` of the record ``path``, or None when the job wrote none (it ran before records
    existed, or was killed)."""
    path = Path(path)
    return float(json.loads(path.read_text())["cpu_s"]) if path.exists() else None
