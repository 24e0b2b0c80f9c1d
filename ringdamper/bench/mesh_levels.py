"""Benchmark of one ring's static and reduction stages on the campaign's mesh refined 1x and 2x.

Per mesh level (every element count of the ``mesh`` section times the factor, as the mesh fidelity
study refines it: ``ringdamper.studies.mesh_convergence.refined``) and per stage, the default ring
runs :func:`ringdamper.static.stage.run_static` or :func:`ringdamper.reduction.stage.run_reduced`
in a fresh process, so that the stage's peak resident memory (``ru_maxrss``) is its own: what one
campaign job of that stage costs on that mesh. CPU seconds are ``time.process_time`` of the stage
(mesh and assembly included, the imports not), wall seconds beside them (the machine is shared).
:func:`run` returns the figures; it asserts nothing.
"""
from __future__ import annotations

import multiprocessing as mp
import resource
import time
import traceback

#: The refinement factors measured (the 2x level takes minutes and ~4 GB).
FACTORS = (1, 2)
STAGES = ("static", "reduction")


def _stage(config: dict, factor: int, stage: str, queue) -> None:
    try:
        queue.put(_timed_stage(config, factor, stage))
    except Exception:  # report, don't hang the parent
        queue.put({"error": traceback.format_exc()})


def _timed_stage(config: dict, factor: int, stage: str) -> dict:
    from ringdamper.reduction.stage import run_reduced
    from ringdamper.static.stage import run_static
    from ringdamper.studies.mesh_convergence import refined

    cfg = refined(config, factor)
    t, c = time.perf_counter(), time.process_time()
    if stage == "static":
        ds = run_static(cfg, (0.0, 0.0, 0.0))[0]
        sizes = {"pairs": ds.sizes["pair"], "status": int(ds.attrs["status"])}
    else:
        ds = run_reduced(cfg, (0.0, 0.0, 0.0))
        sizes = {"dofs_full": int(ds.attrs["dofs_full"]), "dofs_craig_bampton": int(ds.attrs["dofs_craig_bampton"])}
    return {"cpu_s": time.process_time() - c, "wall_s": time.perf_counter() - t,
            "peak_rss_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, **sizes}


def measure(config: dict, factor: int, stage: str) -> dict:
    """CPU, wall seconds and peak RSS (MB) of one stage of the default ring at one mesh level."""
    ctx = mp.get_context("spawn")
    queue = ctx.Queue()
    proc = ctx.Process(target=_stage, args=(config, factor, stage, queue))
    proc.start()
    out = queue.get()
    proc.join()
    return out


def run(config: dict, factors=FACTORS) -> dict:
    """Per mesh level ``"<factor>x"``, per stage: its CPU, wall seconds, peak RSS and sizes."""
    return {f"{factor}x": {stage: measure(config, factor, stage) for stage in STAGES} for factor in factors}
