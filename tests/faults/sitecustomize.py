"""Faults injected into the campaign's jobs by the tests of the failure and kill paths, never by a
real campaign: Python imports this module at the start of every interpreter (Snakemake's and each
job's) whose ``PYTHONPATH`` holds this folder, and it acts only when ``RINGDAMPER_TEST_FAULTS``
names a YAML file (:func:`tests.snakemake_run.run_snakemake` with ``faults=`` sets both). The file
lists geometries by kappa:

- ``static``: their static solve raises, as a solver failure would (the stage writes a failed
  static.nc, status 99, and the campaign goes on);
- ``stall_static``: their static job stops after its two VTU files, before static.nc, logs
  ``stalled by the test`` and waits to be killed, so that a test kills the run at a known point in a
  job with part of its outputs written. It raises if nobody kills it within :data:`STALL_SECONDS`.
"""
import os

#: How long a stalled static job waits to be killed before it fails.
STALL_SECONDS = 600


def _listed(kappa, kappas) -> bool:
    import numpy as np

    return any(np.array_equal(np.asarray(k, dtype=float), np.asarray(kappa, dtype=float)) for k in kappas)


def _install(faults: dict) -> None:
    """Wrap the static stage's solve and the NetCDF writer for the listed geometries."""
    import logging
    import time
    from pathlib import Path

    import ringdamper.io
    import ringdamper.static.stage

    solve, write = ringdamper.static.stage.solve_static, ringdamper.io.write_netcdf

    def failing_solve(model, config):
        if _listed(model.geometry.kappa, faults.get("static", [])):
            raise RuntimeError("fault injected by the test (static)")
        return solve(model, config)

    def stalling_write(ds, path, config=None):
        if Path(path).name == "static.nc" and _listed(ds.attrs["kappa"], faults.get("stall_static", [])):
            logging.getLogger(__name__).warning("kappa=%s stalled by the test: waiting to be killed",
                                                list(ds.attrs["kappa"]))
            time.sleep(STALL_SECONDS)
            raise RuntimeError(f"stalled static job not killed within {STALL_SECONDS} s")
        return write(ds, path, config)

    ringdamper.static.stage.solve_static = failing_solve
    ringdamper.io.write_netcdf = stalling_write


if os.environ.get("RINGDAMPER_TEST_FAULTS"):
    import yaml

    with open(os.environ["RINGDAMPER_TEST_FAULTS"]) as fh:
        _install(yaml.safe_load(fh))
