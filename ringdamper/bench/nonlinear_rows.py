"""Benchmark of the Newton system on the nonlinear contact rows
(:mod:`ringdamper.nonlinear.harmonic_balance.nonlinear_rows`) on the default ring at the campaign's dNNM
settings: per grid point, the order of the full system (trivial unknowns eliminated) and of the reduced
one, and the CPU of a factorisation and one solve of each; and the whole backbone with and without it,
its CPU, its LU count by kind (full, reduced) and
the largest change of ω and ζ. Returns the figures; asserts nothing (speed is measured, never asserted).
"""
from __future__ import annotations

import time

import numpy as np


def run(config: dict) -> dict:
    """The figures of the module docstring for the default ring of ``config``."""
    from ringdamper.bench.dnnm import ring_inputs
    from ringdamper.nonlinear.stage import amplitude_grid, solve_backbone
    from ringdamper.studies.hub_calibration import crossing_speed

    dnnm = config["dnnm"]
    reduced, static = ring_inputs(config, (0.0, 0.0, 0.0))
    backbone, contacts, _, omega0 = solve_backbone(reduced, static, config, crossing_speed(config)[1],
                                                  amplitude_grid(dnnm), dnnm["n_harmonics"],
                                                  dnnm["n_time_samples"])
    return {"points": _points(backbone, omega0), "backbones": _backbones(backbone, dnnm, omega0)}


def _points(backbone, omega0: float) -> list:
    """Per solved grid point past the stuck ones: both systems' orders and CPU (factorise + one solve)."""
    from ringdamper.nonlinear.harmonic_balance.nonlinear_rows import NonlinearRowsSolver, StuckBasis
    from ringdamper.nonlinear.solvers.jacobian import dense
    from ringdamper.nonlinear.solvers.newton import Factorization

    model = backbone.model
    basis = StuckBasis(model, model.contacts.stuck_stiffness(), omega0)
    rng = np.random.default_rng(0)
    rows = []
    for i in np.flatnonzero(np.isfinite(backbone.omega) & (backbone.iterations > 0)):
        ev = backbone.problem(i).fun(backbone.unknowns(i), np.log(backbone.alpha[i]), True)
        b = rng.standard_normal(ev.J.shape[0])
        start = time.process_time()
        full = Factorization(dense(ev.J), ev.trivial, ev.n_core, overwrite=True)
        full.solve(b)
        middle = time.process_time()
        solver = NonlinearRowsSolver(basis, ev.J).factorize()
        solver.solve(b)
        rows.append({"index": int(i), "alpha": float(backbone.alpha[i]), "full_order": int(full.N.size),
                     "reduced_order": int(solver.order), "nonlinear_rows": int(solver.R.size),
                     "full_cpu_s": middle - start, "reduced_cpu_s": time.process_time() - middle})
    return rows


def _backbones(reference, dnnm: dict, omega0: float) -> dict:
    """The backbone solved again with and without the reduced systems: CPU, LUs by kind, changes."""
    from ringdamper.nonlinear.harmonic_balance.epmc import epmc
    from ringdamper.nonlinear.solvers.budget import lu_budget
    from ringdamper.nonlinear.stage import ARC_POINTS

    model = reference.model
    out = {}
    for flag in (False, True):
        start = time.process_time()
        with lu_budget(None) as budget:
            bb = epmc(model.structure, model.contacts, reference.alpha, H=model.H, nt=model.fourier.nt,
                      omega_target=omega0, tol=dnnm.get("continuation_tolerance", 1e-8),
                      max_arc_points=ARC_POINTS, nonlinear_rows=flag)
        cpu = time.process_time() - start
        ok = np.isfinite(bb.omega) & np.isfinite(reference.omega)
        out["nonlinear_rows" if flag else "full"] = {
            "cpu_s": cpu, "lus": budget.used, "full_lus": budget.kinds["full"],
            "reduced_lus": budget.kinds["nonlinear_rows"],
            "omega_change": float(np.max(np.abs(bb.omega[ok] / reference.omega[ok] - 1))),
            "zeta_change_over_max": float(np.max(np.abs(bb.zeta[ok] - reference.zeta[ok]))
                                          / np.max(np.abs(reference.zeta[ok])))}
    return out
