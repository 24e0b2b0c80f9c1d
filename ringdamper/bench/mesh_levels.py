"""Benchmark of one ring's static and reduction stages on the campaign's mesh refined 1x and 2x,
monolithic and on the fixed substructure (``reduction.superelement``, built once per campaign).

Per mesh level (every element count of the ``mesh`` section times the factor, as the mesh fidelity
study refines it: ``ringdamper.studies.mesh_convergence.refined``) and per stage, the default ring
runs :func:`ringdamper.static.stage.run_static` or :func:`ringdamper.reduction.stage.run_reduced`
in a fresh process, so that the stage's peak resident memory (``ru_maxrss``) is its own: what one
campaign job of that stage costs on that mesh. CPU seconds are ``time.process_time`` of the stage
(mesh and assembly included, the imports not), wall seconds beside them (the machine is shared).
The ``superelement`` stage builds and saves the fixed part's super-element (``substructure.n_modes``
of the configuration); ``static_substructured`` and ``reduction_substructured`` read it.
:func:`run` returns the figures; it asserts nothing.
"""
from __future__ import annotations

import copy
import multiprocessing as mp
import resource
import tempfile
import time
import traceback
from pathlib import Path

#: The refinement factors measured (the 2x level takes minutes and ~4 GB).
FACTORS = (1, 2)
STAGES = ("static", "reduction", "superelement", "static_substructured", "reduction_substructured")
#: substructuring settings when the configuration has none
SUBSTRUCTURE = {"enabled": True, "n_modes": 100}


def _stage(config: dict, factor: int, stage: str, queue, folder: str) -> None:
    try:
        queue.put(_timed_stage(config, factor, stage, Path(folder) / f"fixed_part_{factor}x.npz"))
    except Exception:  # report, don't hang the parent
        queue.put({"error": traceback.format_exc()})


def _run(cfg: dict, stage: str, superelement: Path) -> dict:
    """Run one stage of the default ring; its sizes."""
    from ringdamper.reduction.stage import run_reduced
    from ringdamper.reduction.superelement import build_superelement, save
    from ringdamper.static.stage import run_static

    kappa = (0.0, 0.0, 0.0)
    path = superelement if stage.endswith("_substructured") else None
    if stage.startswith("static"):
        ds = run_static(cfg, kappa, path)[0]
        return {"pairs": ds.sizes["pair"], "status": int(ds.attrs["status"])}
    if stage.startswith("reduction"):
        ds = run_reduced(cfg, kappa, path)
        return {"dofs_full": int(ds.attrs["dofs_full"]), "dofs_craig_bampton": int(ds.attrs["dofs_craig_bampton"])}
    se = build_superelement(cfg)
    save(se, superelement)
    return {"boundary_dofs": len(se.boundary), "cpu_parts_s": se.cpu_s}


def _timed_stage(config: dict, factor: int, stage: str, superelement: Path) -> dict:
    from ringdamper.studies.mesh_convergence import refined

    cfg = refined(config, factor)
    cfg.setdefault("substructure", copy.deepcopy(SUBSTRUCTURE))
    t, c = time.perf_counter(), time.process_time()
    sizes = _run(cfg, stage, superelement)
    return {"cpu_s": time.process_time() - c, "wall_s": time.perf_counter() - t,
            "peak_rss_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, **sizes}


def measure(config: dict, factor: int, stage: str, folder: str) -> dict:
    """CPU, wall seconds and peak RSS (MB) of one stage of the default ring at one mesh level
    (``folder`` holds the super-element the substructured stages read)."""
    ctx = mp.get_context("spawn")
    queue = ctx.Queue()
    proc = ctx.Process(target=_stage, args=(config, factor, stage, queue, folder))
    proc.start()
    out = queue.get()
    proc.join()
    return out


def run(config: dict, factors=FACTORS) -> dict:
    """Per mesh level ``"<factor>x"``, per stage: its CPU, wall seconds, peak RSS and sizes."""
    with tempfile.TemporaryDirectory() as folder:
        return {f"{factor}x": {stage: measure(config, factor, stage, folder) for stage in STAGES}
                for factor in factors}
