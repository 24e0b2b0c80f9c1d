"""Benchmark of the contact-pair dial (``mesh.contact_pairs``, :mod:`ringdamper.fem.contact_pairs`) on the
default ring at the default mesh and the campaign's dNNM settings: the node pairs and grids of cell pairs
from 18 to 192, each with its pair count, the nodes the pairs read, the CPU of the FE stages (static and
reduction) and of the dNNM, the stuck target frequency and the backbone's ζ_max with ω0 and |q_res,z|
there, and each one's relative change against the finest grid. Returns the figures; asserts nothing.
"""
from __future__ import annotations

import copy
import time

import numpy as np

GRIDS = ((6, 3), (9, 4), (12, 5), (18, 6), (24, 8))   # n_theta x n_axial; the last is the reference


def _variant(config: dict, placement: dict) -> dict:
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
    i = int(np.nanargmax(ds.zeta.values))
    return {**placement, "pairs": int(static.sizes["pair"]),
            "nodes_read": int(len(build_model(build_sector(cfg, (0.0, 0.0, 0.0)), cfg).pairs.nodes)),
            "fe_cpu_s": fe_cpu, "dnnm_cpu_s": dnnm_cpu, "stuck_hz": float(omega_stuck / (2 * np.pi)),
            "zeta_max": float(ds.zeta.values[i]), "omega0_at_zeta_max": float(ds.omega0.values[i]),
            "q_res_z_at_zeta_max": float(ds.q_res_z.values[i])}


def run(config: dict) -> dict:
    """The figures of the module docstring for the default ring of ``config``."""
    rows = [_variant(config, {"placement": "nodes"})]
    rows += [_variant(config, {"placement": "grid", "n_theta": a, "n_axial": b}) for a, b in GRIDS]
    reference = rows[-1]
    for row in rows:
        for key in ("stuck_hz", "zeta_max", "omega0_at_zeta_max", "q_res_z_at_zeta_max"):
            row[f"{key}_change"] = row[key] / reference[key] - 1.0
    return {"variants": rows, "reference": f"grid {GRIDS[-1][0]} x {GRIDS[-1][1]}"}
