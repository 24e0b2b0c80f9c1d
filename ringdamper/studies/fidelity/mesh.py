"""Mesh dial: frequencies of the target ND's mode families per (refinement factor, element order),
extrapolated to zero element size (Richardson, h = 1 / factor) per element order; errors against the
limit of the highest order.

The mesh levels are modal only (prestressed at operating speed, contact stuck): a 3x quadratic mesh
already takes GBs and minutes for one ND, so the nonlinear chain is not run on refined meshes; the
target-mode error carries over to omega0 one to one (docs/fidelity.md).
"""

from __future__ import annotations

import resource
import time

import numpy as np

from ringdamper.studies.mesh_convergence import family_frequencies, refined

from .quantities import richardson


def mesh_level(config: dict, factor: int, order: int, families) -> dict:
    """One level: model size, ``frequency_<family>`` (Hz), CPU time (s), peak RSS (MB)."""
    cpu = time.process_time()
    row = family_frequencies(refined(config, factor, order), families)
    row = {"factor": factor, "order": order, **row, "cpu_time_s": time.process_time() - cpu,
           "peak_rss_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0}
    return {k: v.item() if isinstance(v, np.generic) else v for k, v in row.items()}


def extrapolate(rows: list[dict], families) -> list[dict]:
    """Per element order with three or more factors: the Richardson limit and order of each family
    from its three finest levels. Every row gains ``error_<family>`` against the limit of the highest
    element order (the best estimate; NaN without one). Returns the limits as rows (order, family,
    limit_hz, p)."""
    limits = []
    for order in sorted({r["order"] for r in rows}):
        levels = sorted((r for r in rows if r["order"] == order), key=lambda r: r["factor"])
        for fam in families:
            f0, p = np.nan, np.nan
            if len(levels) >= 3:
                last = levels[-3:]
                try:
                    f0, p = richardson([1.0 / r["factor"] for r in last], [r[f"frequency_{fam}"] for r in last])
                except ValueError:
                    pass
            limits.append({"order": order, "family": fam, "limit_hz": f0, "p": p})
    for fam in families:
        best = [lim["limit_hz"] for lim in limits if lim["family"] == fam and np.isfinite(lim["limit_hz"])]
        for r in rows:
            r[f"error_{fam}"] = r[f"frequency_{fam}"] / best[-1] - 1.0 if best else np.nan
    return limits
