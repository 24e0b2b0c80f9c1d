"""Benchmark of the contact-pair dial (``mesh.contact_pairs``, :mod:`ringdamper.fem.contact_pairs`) on the
default ring at the default mesh and the campaign's dNNM settings: the node pairs and grids of cell pairs
from 18 to 192, each with its pair count, the nodes the pairs read, the CPU of the FE stages (static and
reduction) and of the dNNM, the stuck target frequency, and what users read off the backbone
(:func:`ringdamper.studies.fidelity.quantities.user_quantities`: ζ_max and |q_res,z| there, the
frequencies at the first and last response level, |q_res,z| at Table 3's forcing levels γ₁..γ₄ read on
the finest grid's backbone), each with its relative change against the finest grid. Returns the
figures; asserts nothing.
"""
from __future__ import annotations

import copy
import time

import numpy as np

GRIDS = ((6, 3), (9, 4), (12, 5), (18, 6), (24, 8))   # n_theta x n_axial; the last is the reference


def _variant(config: dict, placement: dict) -> tuple:
    from ringdamper.bench.dnnm import ring_inputs
    from ringdamper.fem.model import build_model
    from ringdamper.geometry.sector import build_sector
    from ringdamper.nonlinear.stage import (
        contacts_from_static,
        run_dnnm,
        structure_from_reduced,
        target_stuck_frequency,
    )
    from ringdamper.studies.hub_calibration import crossing_speed

    cfg = copy.deepcopy(config)
    cfg["mesh"]["contact_pairs"] = placement
    start = time.process_time()
    reduced, static = ring_inputs(cfg, (0.0, 0.0, 0.0))
    fe_cpu = time.process_time() - start
    target_hz = crossing_speed(cfg)[1]
    contacts = contacts_from_static(static, cfg["contact"], cfg["dnnm"]["friction_law"])
    omega_stuck = target_stuck_frequency(structure_from_reduced(reduced, 1), contacts, target_hz)
    start = time.process_time()
    ds = run_dnnm(reduced, static, cfg, target_hz, omega_stuck)
    dnnm_cpu = time.process_time() - start
    return ds, {**placement, "pairs": int(static.sizes["pair"]),
                "nodes_read": int(len(build_model(build_sector(cfg, (0.0, 0.0, 0.0)), cfg).pairs.nodes)),
                "fe_cpu_s": fe_cpu, "dnnm_cpu_s": dnnm_cpu, "stuck_hz": float(omega_stuck / (2 * np.pi))}


def run(config: dict) -> dict:
    """The figures of the module docstring for the default ring of ``config``."""
    from ringdamper.studies.fidelity.quantities import gamma_at, relative_errors, user_quantities

    placements = [{"placement": "nodes"}] + [{"placement": "grid", "n_theta": a, "n_axial": b} for a, b in GRIDS]
    cases = [_variant(config, p) for p in placements]
    gammas = gamma_at(cases[-1][0], config["frf"]["target_amplitudes"])
    args = (config["sensitivity"]["levels"], gammas, config["exploration"]["optimum_max_level"])
    reference = {**user_quantities(cases[-1][0], *args), "stuck_hz": cases[-1][1]["stuck_hz"]}
    rows = []
    for ds, row in cases:
        values = {**user_quantities(ds, *args), "stuck_hz": row["stuck_hz"]}
        rows.append({**row, **values, **{f"{k}_error": v for k, v in relative_errors(values, reference).items()}})
    return {"variants": rows, "reference": f"grid {GRIDS[-1][0]} x {GRIDS[-1][1]}",
            "gammas_n": gammas.tolist()}
