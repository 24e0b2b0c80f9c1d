"""Run the repository's Snakefile in a subprocess, as a user would, on a configuration and a results
folder of the test's own (shared by the workflow tests)."""
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import yaml

REPO = Path(__file__).resolve().parent.parent
SMALL_CONFIG = REPO / "tests" / "config_small.yaml"  # the coarse test campaign


def snakemake_command(results, configfile, *args, cores=1) -> list[str]:
    """The command line of ``snakemake *args`` (targets and flags) with ``configfile``, writing into
    ``results``; without Snakemake's locks (``--nolock``): every test's results folder is its own, and
    the runs of the tests share the repository as working directory, whose ``.snakemake/locks`` folder
    a run removes whole when it ends, under another run still building its DAG."""
    return [sys.executable, "-m", "snakemake", *map(str, args), "--nolock", "--snakefile", str(REPO / "Snakefile"),
            "--directory", str(REPO), "--configfile", str(configfile), "--cores", str(cores),
            "--config", f"results={results}"]  # last: --config takes every following key=value


def effective_config(configfile) -> dict:
    """The configuration a run with ``--configfile configfile`` sees: the Snakefile's own
    ``config.yaml``, updated key by key with ``configfile`` (Snakemake merges them so)."""
    from snakemake.common.configfile import load_configfile
    from snakemake.utils import update_config

    config = load_configfile(REPO / "config.yaml")
    update_config(config, load_configfile(configfile))
    return config


def fault_environment(faults: dict, folder) -> dict:
    """The environment of a run whose jobs suffer ``faults`` (``tests/faults/sitecustomize.py``: kind
    -> list of kappa), written to ``folder``/faults.yaml."""
    path = Path(folder) / "faults.yaml"
    path.write_text(yaml.safe_dump(faults))
    python_path = os.pathsep.join(filter(None, [str(REPO / "tests" / "faults"), str(REPO),
                                                os.environ.get("PYTHONPATH")]))
    return dict(os.environ, PYTHONPATH=python_path, RINGDAMPER_TEST_FAULTS=str(path))


def run_snakemake(results, configfile, *args, cores=1, timeout=900, env=None):
    """Run :func:`snakemake_command` to its end (output captured), in ``env`` (default: this
    process's environment)."""
    return subprocess.run(snakemake_command(results, configfile, *args, cores=cores), capture_output=True,
                          text=True, timeout=timeout, env=env)


def dry_run_jobs(results, configfile, *args) -> dict:
    """rule -> number of jobs a dry run of ``snakemake *args`` would run (its "Job stats" table; empty
    when there is nothing to be done)."""
    run = run_snakemake(results, configfile, "--dry-run", *args)
    assert run.returncode == 0, failure_tail(run)
    lines = (run.stdout + run.stderr).splitlines()
    if not any(line.startswith("Job stats:") for line in lines):
        return {}
    table = lines[[i for i, line in enumerate(lines) if line.startswith("Job stats:")][0] + 3:]
    jobs = {}
    for line in table:
        fields = line.split()
        if len(fields) != 2 or fields[0] == "total":
            break
        jobs[fields[0]] = int(fields[1])
    return jobs


def kill_when(results, configfile, targets, env, reached, what: str, timeout: float = 600):
    """Run Snakemake towards ``targets`` in a process group of its own and SIGKILL the whole group as
    soon as ``reached()`` holds (a user's kill -9 in the middle of a run); fail naming ``what`` if the
    run ends first or ``timeout`` seconds pass."""
    proc = subprocess.Popen(snakemake_command(results, configfile, *targets, cores=2), start_new_session=True,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env)
    deadline = time.monotonic() + timeout
    while not reached():
        assert proc.poll() is None, "the run ended before it could be killed"
        assert time.monotonic() < deadline, f"{what} not reached in {timeout:g} s"
        time.sleep(0.05)
    os.killpg(proc.pid, signal.SIGKILL)
    proc.wait()


def failure_tail(run, chars: int = 3000) -> str:
    """The end of a finished run's stdout and stderr, for an assertion's message: Snakemake writes a
    dry run's errors to stdout, its log to stderr."""
    return f"stdout:\n{run.stdout[-chars:]}\nstderr:\n{run.stderr[-chars:]}"
