"""Timing of the static contact solver on a synthetic ≈15k-DoF two-block case
(:func:`ringdamper.static.synthetic.two_blocks`), run by ``python -m ringdamper.bench --only
static_synthetic``. Reports the DoF and pair counts, the assembly time and, per method, the solve
time, iterations, residuals and the number of closed pairs. Timings are reported, never asserted.
"""
import time

import numpy as np

from ringdamper.static.solver import solve_static_contact
from ringdamper.static.synthetic import two_blocks


def run(linear: bool = False) -> dict:
    """Q2 (27-node) bricks by default, Q1 bricks with ``linear``."""
    nx, nz = (12, 14) if linear else (6, 7)
    t = time.perf_counter()
    system = two_blocks(nx=nx, nz=nz, height=1.0, quadratic=not linear,
                        gap=lambda x, y: 0.3 * ((x - 0.5) ** 2 + (y - 0.5) ** 2))
    out = {"element": "Q1" if linear else "Q2", "dofs": int(system.K.shape[0]),
           "pairs": int(system.g0.size), "assembly_s": time.perf_counter() - t}
    for method in ("penalty", "lagrange"):
        t = time.perf_counter()
        r = solve_static_contact(system.K, system.f, system.G, system.g0, 1e4, 1e3, method=method)
        out[method] = {"solve_s": time.perf_counter() - t, "status": int(r.status), "reason": r.reason,
                       "iterations": int(r.iterations), "residual": float(r.residual),
                       "complementarity": float(r.complementarity),
                       "closed_pairs": int(np.count_nonzero(r.in_contact)), "sum_N": float(r.N0.sum())}
    return out
