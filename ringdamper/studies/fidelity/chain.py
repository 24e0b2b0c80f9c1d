"""One case of the per-geometry chain (static -> reduction -> dNNM + E-EBM), timed stage by stage.

Wall times are ``time.perf_counter`` per stage and CPU times ``time.process_time`` (the wall time on
an idle core: the machine is shared, so the charts use the CPU time); the peak memory is the process's maximum resident
set size (``resource.getrusage``), meaningful because every case runs in its own Snakemake job.
"""

from __future__ import annotations

import resource
import time

import xarray as xr

from ringdamper.nonlinear.stage import run_dnnm
from ringdamper.reduction.stage import run_reduced
from ringdamper.static.stage import run_static


def run_case(config: dict, kappa, target_hz: float) -> xr.Dataset:
    """dnnm.nc of ``kappa`` under ``config`` with the stage wall times (s) and the peak RSS (MB)
    as attributes. The frequency normalisation is 1 (the study compares ``frequency`` in Hz)."""
    clock = [(time.perf_counter(), time.process_time())]
    static, _, _ = run_static(config, kappa)
    if static.attrs["status"] != 0:
        raise RuntimeError(f"static solve failed for kappa={list(kappa)}: {static.attrs['reason']}")
    clock.append((time.perf_counter(), time.process_time()))
    reduced = run_reduced(config, kappa)
    clock.append((time.perf_counter(), time.process_time()))
    ds = run_dnnm(reduced, static, config, target_hz, 1.0)
    clock.append((time.perf_counter(), time.process_time()))
    for i, stage in enumerate(("static", "reduction", "dnnm")):
        ds.attrs[f"{stage}_time_s"] = clock[i + 1][0] - clock[i][0]
        ds.attrs[f"{stage}_cpu_s"] = clock[i + 1][1] - clock[i][1]
    ds.attrs.update({"chain_time_s": clock[-1][0] - clock[0][0], "chain_cpu_s": clock[-1][1] - clock[0][1],
                     "peak_rss_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0})
    return ds
