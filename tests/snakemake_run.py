"""Run the repository's Snakefile in a subprocess, as a user would, on a configuration and a results
folder of the test's own (shared by the workflow tests)."""
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
SMALL_CONFIG = REPO / "tests" / "config_small.yaml"  # the coarse test campaign


def snakemake_command(results, configfile, *args, cores=1) -> list[str]:
    """The command line of ``snakemake *args`` (targets and flags) with ``configfile``, writing into
    ``results``."""
    return [sys.executable, "-m", "snakemake", *map(str, args), "--snakefile", str(REPO / "Snakefile"),
            "--directory", str(REPO), "--configfile", str(configfile), "--cores", str(cores),
            "--config", f"results={results}"]  # last: --config takes every following key=value


def run_snakemake(results, configfile, *args, cores=1, timeout=900):
    """Run :func:`snakemake_command` to its end (output captured)."""
    return subprocess.run(snakemake_command(results, configfile, *args, cores=cores), capture_output=True,
                          text=True, timeout=timeout)
