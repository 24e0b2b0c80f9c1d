"""Benchmarks (``make bench``): wall time, peak memory and sizes of each stage, written to files.

Speed is measured here, never asserted in tests (docs/design.md §8). Each benchmark runs in its own process
so that peak memory (ru_maxrss) belongs to it alone, on one core as a campaign job does (Snakemake gives a
one-thread rule ``OMP_NUM_THREADS=1`` and its kin): :func:`main` sets those variables
(:data:`ringdamper.workers.THREAD_VARIABLES`) to 1 unless the caller's environment chose them.
"""

from __future__ import annotations

import argparse
import json
import multiprocessing as mp
import os
import resource
import time
import traceback
from pathlib import Path

import numpy as np

from ringdamper.bench.machine import describe
from ringdamper.config import load_config
from ringdamper.status import usable_status
from ringdamper.workers import THREAD_VARIABLES


def _fe_chain(config: dict) -> dict:
    """Mesh + assembly + ND diagram + Campbell of the default ring (the modal stage)."""
    from ringdamper.fem.model import build_model, stuck_contact_stiffness
    from ringdamper.geometry.sector import build_sector
    from ringdamper.modal.stage import run_modal_stage

    out = {}
    t = time.perf_counter()
    sector = build_sector(config, (0.0, 0.0, 0.0))
    out["mesh_s"] = time.perf_counter() - t
    t = time.perf_counter()
    model = build_model(sector, config)
    stuck_contact_stiffness(model, config["contact"])
    out["assembly_s"] = time.perf_counter() - t
    out.update(dofs=model.n_dofs, elements=int(sector.mesh.t.shape[1]), pairs=len(model.pairs),
               element_order=model.element_order)
    t = time.perf_counter()
    res = run_modal_stage(config)
    out["modal_stage_s"] = time.perf_counter() - t
    out["crossing_speed_rpm"] = res.resonance["speed_rpm"]
    out["crossing_frequency_hz"] = res.resonance["frequency_hz"]
    return out


def _static_chain(config: dict) -> dict:
    """mesh -> model -> static contact for the reference rings (per-geometry times)."""
    from ringdamper.campaign.design_space import REFERENCE_RINGS
    from ringdamper.fem.model import build_model
    from ringdamper.geometry.sector import build_sector
    from ringdamper.static.stage import solve_static

    rows = []
    for label, kappa in REFERENCE_RINGS.items():
        t = time.perf_counter()
        model = build_model(build_sector(config, kappa), config)
        t_model = time.perf_counter() - t
        result, _ = solve_static(model, config)
        rows.append({"ring": label, "kappa": list(kappa), "model_s": t_model,
                     "static_s": time.perf_counter() - t - t_model, "status": result.status,
                     "in_contact": int(result.in_contact.sum()), "pairs": len(model.pairs),
                     "N0_sum_N": float(result.N0.sum()), "N0_max_N": float(result.N0.max()),
                     "gap_max_m": float(result.gap.max()), "iterations": result.iterations})
    return {"rings": rows}


def _geometry_chain(config: dict) -> dict:
    """The per-geometry chain on the default ring, one core: mesh -> static -> reduced -> dnnm
    (H = 1, the campaign's H and 5), one forced-response curve (H = 1) through the E-EBM point of
    largest damping, with its peak against the E-EBM prediction, and Table 3's forced responses
    of the default ring at the campaign's H (points, seconds, peaks)."""
    from ringdamper.fem.model import build_model
    from ringdamper.geometry.sector import build_sector
    from ringdamper.nonlinear.stage import (
        contacts_from_static,
        run_dnnm,
        structure_from_reduced,
        target_stuck_frequency,
    )
    from ringdamper.reduction import modal_basis, reduce_sector, reduced_dataset
    from ringdamper.reduction.stage import reduction_sizes
    from ringdamper.static.stage import solve_static, static_dataset
    from ringdamper.studies.hub_calibration import crossing_speed

    kappa = (0.0, 0.0, 0.0)
    times = {}
    t = time.perf_counter()
    model = build_model(build_sector(config, kappa), config)
    times["mesh_model_s"] = time.perf_counter() - t
    t = time.perf_counter()
    result, prob = solve_static(model, config)
    static = static_dataset(model, result, prob, kappa, config["operation"]["speed_rpm"])
    times["static_s"] = time.perf_counter() - t
    t = time.perf_counter()
    def reduced_model(n_harmonics):
        rs = reduce_sector(model, config["operation"]["engine_order"], n_harmonics=n_harmonics,
                           **reduction_sizes(config))
        return reduced_dataset(rs, kappa, [modal_basis(rh, rs.response_index) for rh in rs.harmonics])

    reduced = reduced_model(config["reduction"]["n_harmonics"])
    times["reduced_s"] = time.perf_counter() - t
    harmonics = sorted({1, config["dnnm"]["n_harmonics"], 5})
    # the comparison at higher H than the campaign keeps needs its own (untimed) reduced model
    reduced_all = reduced if harmonics[-1] <= config["reduction"]["n_harmonics"] else reduced_model(harmonics[-1])
    # the target mode: nearest the EO x target-family crossing (the modal stage's resonance)
    target_hz = crossing_speed(config)[1]
    structure = structure_from_reduced(reduced, 1)
    contacts = contacts_from_static(static, config["contact"], config["dnnm"]["friction_law"])
    w_default = target_stuck_frequency(structure, contacts, target_hz)
    out = {}
    backbones = {}
    for H in harmonics:
        cfg = {**config, "dnnm": {**config["dnnm"], "n_harmonics": H, "max_harmonics": H,
                                  "n_time_samples": max(config["dnnm"]["n_time_samples"], 4 * H + 4)}}
        t = time.perf_counter()
        ds = run_dnnm(reduced_all, static, cfg, target_hz, w_default)
        out[f"dnnm_H{H}_s"] = time.perf_counter() - t
        out[f"dnnm_H{H}_status_counts"] = np.bincount(ds.status.values.astype(int), minlength=5).tolist()
        out[f"dnnm_H{H}_zeta_max"] = float(np.nanmax(ds.zeta.values))
        backbones[H] = ds
    out["frf_H1"] = _default_frf(reduced, contacts, backbones[1], config)
    out["frf_table3"] = _table3_frf(reduced, contacts, backbones[config["dnnm"]["n_harmonics"]], config,
                                    w_default)
    times.update(out)
    times["chain_default_H_s"] = (times["mesh_model_s"] + times["static_s"] + times["reduced_s"]
                                  + out[f"dnnm_H{config['dnnm']['n_harmonics']}_s"])
    return times


def _default_frf(reduced, contacts, backbone, config: dict) -> dict:
    """Forced response (H = 1, EO forcing γ of the E-EBM at the damping peak, ζs of the config)
    over ±1.5 % around that point's frequency; time and peak / E-EBM amplitude."""
    from ringdamper.bench.dynamics import time_frf
    from ringdamper.nonlinear.stage import structure_from_reduced

    ok = usable_status(backbone.status.values)
    mid = int(np.nanargmax(np.where(ok, backbone.zeta.values, np.nan)))
    return time_frf(structure_from_reduced(reduced, 1), contacts, float(backbone.gamma.values[mid]),
                    2 * np.pi * float(backbone.frequency.values[mid]),
                    float(backbone.q_res_z.values[mid]), 1,
                    config["dnnm"]["structural_damping_ratio"], (0.985, 1.015))


def _table3_frf(reduced, contacts, backbone, config: dict, omega_reference: float) -> list:
    """Table 3's forced responses of the default ring (``frf`` section: the levels of the target
    amplitudes, the band; the backbone's H, Nt and ζs), as the ``frf_curve`` rule computes them: per
    level the points, wall and CPU seconds, status and the refined peak."""
    from ringdamper.campaign.forced_check import EEBMBackbone, forced_curve, forcing_levels
    from ringdamper.nonlinear.stage import structure_from_reduced

    H, nt = config["dnnm"]["n_harmonics"], config["dnnm"]["n_time_samples"]
    bb = EEBMBackbone.from_dnnm(backbone)
    structure = structure_from_reduced(reduced, H)
    rows = []
    for level, gamma in enumerate(forcing_levels(bb, config["frf"]["target_amplitudes"]), 1):
        t, c = time.perf_counter(), time.process_time()
        ds = forced_curve(structure, contacts, bb, float(gamma), H=H, nt=nt,
                          zeta_s=config["dnnm"]["structural_damping_ratio"], band=config["frf"]["frequency_band"],
                          omega_reference=omega_reference)
        rows.append({"level": level, "gamma_N": float(gamma), "points": int(ds.sizes["point"]),
                     "seconds": time.perf_counter() - t, "cpu_seconds": time.process_time() - c,
                     "status": int(ds.status), "peak_amplitude_m": float(ds.peak_amplitude),
                     "peak_frequency_hz": float(ds.peak_frequency), "eebm_amplitude_m": float(ds.eebm_amplitude)})
    return rows


def _dynamics_synthetic(config: dict) -> dict:
    """The dynamics core on a synthetic system of the real size (ringdamper.bench.dynamics)."""
    from ringdamper.bench.dynamics import run

    return run()


def _static_synthetic(config: dict) -> dict:
    """The static contact solver on a synthetic two-block case (ringdamper.bench.static_synthetic)."""
    from ringdamper.bench.static_synthetic import run

    return {"Q2": run(linear=False), "Q1": run(linear=True)}


def _mesh_convergence(config: dict) -> dict:
    from ringdamper.studies.mesh_convergence import mesh_study

    return {"levels": mesh_study(config, config["studies"]["mesh_convergence"]["levels"])}


def _reduction(config: dict) -> dict:
    """CPU seconds per part of the reduction stage (rule ``reduced``) on two rings (ringdamper.bench.reduction)."""
    from ringdamper.bench.reduction import run

    return run(config)


def _mesh_levels(config: dict) -> dict:
    """The default ring's static and reduction stages, monolithic and on the fixed substructure, and
    the super-element's build, each in its own process, on the 1x and 2x meshes: CPU, wall, peak
    memory (ringdamper.bench.mesh_levels)."""
    from ringdamper.bench.mesh_levels import run

    return run(config)


def _dnnm(config: dict) -> dict:
    """dNNM CPU time of the default ring (and its profile), of rings at the median cost and of the hard rings
    (ringdamper.bench.dnnm)."""
    from ringdamper.bench.dnnm import run

    return run(config)


def _nonlinear_rows(config: dict) -> dict:
    """The Newton system on the nonlinear contact rows against the full one on the default ring
    (ringdamper.bench.nonlinear_rows)."""
    from ringdamper.bench.nonlinear_rows import run

    return run(config)


def _contact_pairs(config: dict) -> dict:
    """The contact-pair dial on the default ring: node pairs and grids of 18 to 192 cell pairs
    (ringdamper.bench.contact_pairs)."""
    from ringdamper.bench.contact_pairs import run

    return run(config)


def _coulomb(config: dict) -> dict:
    """The Coulomb law's AFT on the default ring's backbone states, against the former march
    (ringdamper.bench.coulomb)."""
    from ringdamper.bench.coulomb import run

    return run(config)


def _library(config: dict) -> dict:
    """NLvib's example systems 05 and 07 as docs/examples computes them (ringdamper.bench.library)."""
    from ringdamper.bench.library import run

    return run(config)


def _surrogate(config: dict) -> dict:
    """Kriging (120 models) + 50³ grid + Sobol on synthetic data of the campaign's size."""
    from ringdamper.bench.surrogate import run

    return run(config.get("surrogate"))


BENCHMARKS = {"fe_model": _fe_chain, "static": _static_chain, "geometry_chain": _geometry_chain,
              "reduction": _reduction, "dnnm": _dnnm, "nonlinear_rows": _nonlinear_rows,
              "contact_pairs": _contact_pairs,
              "coulomb": _coulomb, "library": _library,
              "dynamics_synthetic": _dynamics_synthetic,
              "static_synthetic": _static_synthetic,
              "mesh_convergence": _mesh_convergence, "mesh_levels": _mesh_levels, "surrogate": _surrogate}


def _run_one(name, config, queue):
    start = time.perf_counter()
    try:
        result = BENCHMARKS[name](config)
    except Exception:  # report, don't hang the parent
        result = {"error": traceback.format_exc()}
    result["total_wall_s"] = time.perf_counter() - start
    result["peak_rss_mb"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    queue.put(result)


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--out", default="results/benchmarks")
    parser.add_argument("--config", default=None)
    parser.add_argument("--only", nargs="*", choices=sorted(BENCHMARKS))
    args = parser.parse_args(argv)
    config = load_config(args.config) if args.config else load_config()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    for var in THREAD_VARIABLES:                      # read by the spawned processes' BLAS: one core
        os.environ.setdefault(var, "1")
    ctx = mp.get_context("spawn")
    machine = describe()
    for name in args.only or BENCHMARKS:
        queue = ctx.Queue()
        proc = ctx.Process(target=_run_one, args=(name, config, queue))
        proc.start()
        result = queue.get()
        proc.join()
        result["machine"] = machine
        (out / f"{name}.json").write_text(json.dumps(result, indent=2))
        print(f"{name}: {json.dumps(result)}")
