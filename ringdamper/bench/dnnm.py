"""Benchmark of the dNNM stage on real rings: CPU time per ring and the profile of the default ring.

The rings: the default ring, three rings at the paper design's median cost :data:`MEDIAN_RINGS` and its
hard rings :data:`HARD_RINGS` (gids of the paper design, :func:`ringdamper.campaign.sampling.make_samples`),
each through mesh -> static -> reduced (untimed) -> dNNM at the campaign's fidelity (timed, CPU seconds
of this process, and the same in reference LUs of this process, :mod:`ringdamper.bench.machine`, the
figure meant to compare between machines). The median rings give the campaign's typical dNNM
(``median_cpu_s``, their median) and the tail against it (``cpu_max_over_median``): the default ring,
whose top dozen points the gauge holds, costs more than a typical ring. The default ring's dNNM is
also run under cProfile: LU factorisations, residual evaluations and the top functions.
:func:`run` returns the figures; it asserts nothing (speed is measured, never asserted).
"""
from __future__ import annotations

import cProfile
import io
import pstats
import time

import numpy as np

#: Rings of the paper design (``sampling.design: paper``) whose dNNM cost 5-20x the median in a
#: campaign run (the tail the step control must handle).
HARD_RINGS = ("t034", "t039", "t036", "t052", "t066")

#: Rings of the paper design whose dNNM cost the median of its 121 rings in a campaign run (7.6-7.7 s
#: of job CPU with the imports, 2026-11-29): the typical ring the per-ring target is about.
MEDIAN_RINGS = ("t024", "t064", "t015")


def ring_inputs(config: dict, kappa) -> tuple:
    """``(reduced, static)`` datasets of the ring ``kappa`` (the campaign's stage functions)."""
    from ringdamper.reduction.stage import run_reduced
    from ringdamper.static.stage import run_static

    static, _, _ = run_static(config, kappa)
    return run_reduced(config, kappa), static


def time_dnnm(config: dict, reduced, static, normalisation: dict, profile: bool = False) -> dict:
    """CPU seconds, statuses and (``profile``) the cProfile figures of one ring's dNNM."""
    from ringdamper.nonlinear.stage import run_dnnm

    prof = cProfile.Profile() if profile else None
    start = time.process_time()
    if prof:
        prof.enable()
    ds = run_dnnm(reduced, static, config, normalisation["target_frequency_hz"],
                  normalisation["omega_stuck_default_rad_s"])
    if prof:
        prof.disable()
    out = {"cpu_s": time.process_time() - start, "status": ds.status.values.astype(int).tolist()}
    if prof:
        out["profile"] = _profile_figures(prof)
    return out


def _profile_figures(prof: cProfile.Profile, top: int = 12) -> dict:
    """Calls and time of the LU factorisations, residual evaluations and the condition numbers of the
    converged points' Jacobians, and the top functions by internal time (under the profiler's overhead)."""
    stats = pstats.Stats(prof, stream=io.StringIO())
    rows = {f"{path.rsplit('/', 1)[-1]}:{name}": (cc, tt, ct)
            for (path, _, name), (cc, _, tt, ct, _) in stats.stats.items()}

    def calls(key):
        return next(({"calls": v[0], "cumulative_s": v[2]} for k, v in rows.items() if k.endswith(key)), None)

    ranked = sorted(rows.items(), key=lambda kv: -kv[1][1])[:top]
    return {"lu_factor": calls("_decomp_lu.py:lu_factor"), "evaluate": calls("condensed.py:evaluate"),
            "contact_aft": calls("friction.py:contact_aft"),
            "conditioning": calls("conditioning.py:backbone_conditions"),
            "top": [{"function": k, "calls": v[0], "internal_s": v[1]} for k, v in ranked]}


def run(config: dict, rings=MEDIAN_RINGS + HARD_RINGS, median_rings=MEDIAN_RINGS) -> dict:
    """The default ring (with its profile) and ``rings`` (gids of the paper design), with the median of
    ``median_rings`` (among ``rings``) and the largest CPU over it."""
    from ringdamper.bench.machine import reference_lu_seconds
    from ringdamper.campaign.sampling import make_samples
    from ringdamper.nonlinear.stage import default_normalisation
    from ringdamper.studies.hub_calibration import crossing_speed

    reduced, static = ring_inputs(config, (0.0, 0.0, 0.0))
    normalisation = default_normalisation(reduced, static, config, crossing_speed(config)[1])
    out = {"default": time_dnnm(config, reduced, static, normalisation)}
    out["default_profiled"] = time_dnnm(config, reduced, static, normalisation, profile=True)
    samples = make_samples({**config["sampling"], "design": "paper"}).set_index("gid")
    for gid in rings:
        kappa = tuple(float(samples.loc[gid, k]) for k in ("kappa1", "kappa2", "kappa3"))
        reduced, static = ring_inputs(config, kappa)
        out[gid] = {"kappa": list(kappa), **time_dnnm(config, reduced, static, normalisation)}
    lu = reference_lu_seconds()
    for k in ("default", *rings):
        out[k]["cpu_reference_lus"] = out[k]["cpu_s"] / lu
    cpu = np.array([out[k]["cpu_s"] for k in ("default", *rings)])
    out["cpu_max_over_default"] = float(cpu.max() / out["default"]["cpu_s"])
    if median_rings:
        out["median_cpu_s"] = float(np.median([out[k]["cpu_s"] for k in median_rings]))
        out["cpu_max_over_median"] = float(cpu.max() / out["median_cpu_s"])
    out["reference_lu_s"] = lu
    return out
