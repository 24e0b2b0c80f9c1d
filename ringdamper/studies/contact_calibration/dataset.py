"""The stages of the contact calibration and their results: the trials of a stage
(:func:`stage_trials`), run over worker processes (:func:`run_stage`), their backbones stored as one
``.npz`` per stage (:func:`save_curves`, :func:`curve_of`), and the curves the study's figures draw
(:func:`figure_curves`). The rows of a stage are written by the rule as its CSV.
"""

from __future__ import annotations

import functools
import itertools
from pathlib import Path

import numpy as np

from ...workers import worker_pool
from .trial import contact_section, in_plausible_range, run_trials


def grid_contacts(grid: dict) -> list[dict]:
    """Every ``contact:`` section of a grid over (μ, kn per area, kt/kn), inside :data:`.trial.PLAUSIBLE`."""
    return [c for c in (contact_section(mu, kn, r) for mu, kn, r in itertools.product(
        grid["friction_coefficient"], grid["normal_stiffness_per_area"], grid["kt_over_kn"]))
        if in_plausible_range(c)]


STAGES = ("coarse", "refine", "harmonics_A", "harmonics_B")

#: The stages whose backbones the figures draw (:func:`figure_curves`).
FIGURE_STAGES = ("coarse", "refine", "harmonics_A")


def stage_trials(config: dict, stage: str) -> list[tuple[dict, int]]:
    """(contact section, H) of every trial of a stage of the study: the ``coarse`` and ``refine``
    grids at H = 1; ``harmonics_A`` the chosen set (``contact:``), ``harmonics_B`` the runner-up,
    at each H of ``harmonics``."""
    study = config["studies"]["contact_calibration"]
    if stage in ("coarse", "refine"):
        return [(c, 1) for c in grid_contacts(study[stage])]
    if stage == "harmonics_A":
        chosen = config["contact"]
    elif stage == "harmonics_B":
        r = study["runner_up"]
        chosen = contact_section(r["friction_coefficient"], r["normal_stiffness_per_area"], r["kt_over_kn"])
    else:
        raise ValueError(f"stage must be one of {STAGES}, got {stage!r}")
    return [(dict(chosen), int(H)) for H in study["harmonics"]]


def run_stage(config: dict, reduced_path, target_hz: float, stage: str, processes: int = 2):
    """All trials of ``stage`` (:func:`stage_trials`) on the study's α grid: ``[(row, curve)]`` in
    the order of the trials. The trials are dealt in turn to up to ``processes`` spawned single-threaded
    worker processes, each running its share on one default ring loaded once (:func:`.trial.run_trials`,
    which gets everything it needs as arguments)."""
    alpha = tuple(config["studies"]["contact_calibration"]["amplitudes"])
    trials = stage_trials(config, stage)
    n = max(1, min(processes, len(trials)))
    run = functools.partial(run_trials, config, reduced_path, target_hz, alpha)
    if n == 1:
        return run(trials)
    with worker_pool(n, "spawn") as pool:
        shares = list(pool.map(run, [trials[k::n] for k in range(n)]))
    out = [None] * len(trials)
    for k, share in enumerate(shares):
        out[k::n] = share
    return out


def save_curves(results, path) -> None:
    """Backbone curves of a stage as one .npz (arrays stacked per trial; NaN for failed trials)."""
    n = max((len(c["alpha"]) for _, c in results if c is not None), default=0)
    out = {}
    for key in ("alpha", "q", "omega0", "zeta", "gamma", "status"):
        out[key] = np.array([c[key] if c is not None else np.full(n, np.nan) for _, c in results],
                            dtype=float)
    for key in ("friction_coefficient", "normal_stiffness_per_area", "tangential_stiffness_per_area", "H"):
        out[key] = np.array([r.get(key, np.nan) for r, _ in results], dtype=float)
    np.savez_compressed(path, **out)


def curve_of(npz_path, mu: float, kn: float, ratio: float, H: int = 1) -> dict:
    """One backbone from a stage's .npz (see :func:`save_curves`), None if the stage lacks it."""
    d = np.load(npz_path)
    ok = (np.isclose(d["friction_coefficient"], mu) & np.isclose(d["normal_stiffness_per_area"], kn)
          & np.isclose(d["tangential_stiffness_per_area"], ratio * kn) & (d["H"] == H))
    if not ok.any():
        return None
    i = int(np.flatnonzero(ok)[0])
    return {k: d[k][i] for k in ("alpha", "q", "omega0", "zeta", "gamma", "status")}


def figure_curves(config: dict, curves_dir) -> tuple[list, list]:
    """The labelled curves ``[(label, curve)]`` of the study's two figures, from the stages' .npz in
    ``curves_dir``: the chosen backbone (``contact:``) at each H of the study with its H = 1
    neighbours of the refinement grid, and the chosen H = 1 backbone against the ``example_curves``
    of the coarse grid. Curves a stage lacks are left out."""
    cd = Path(curves_dir)
    c = config["contact"]
    chosen = (c["friction_coefficient"], c["normal_stiffness_per_area"],
              c["tangential_stiffness_per_area"] / c["normal_stiffness_per_area"])
    study = config["studies"]["contact_calibration"]
    label = f"chosen: mu {chosen[0]:g}, kn {chosen[1]:g}, kt/kn {chosen[2]:g}"
    curves = [(f"{label}, H={H}", curve_of(cd / "harmonics_A.npz", *chosen, H=H)) for H in study["harmonics"]]
    neighbours = [(mu, kn, r) for mu, kn, r in itertools.product(*(study["refine"][k] for k in (
        "friction_coefficient", "normal_stiffness_per_area", "kt_over_kn")))
        if sum(a != b for a, b in zip((mu, kn, r), chosen)) == 1]
    for mu, kn, r in neighbours:
        curve = curve_of(cd / "refine.npz", mu, kn, r)
        if curve is not None:
            curves.append((f"mu {mu:g}, kn {kn:g}, kt/kn {r:g} (H=1)", curve))
    others = [(f"{label}, H=1", curve_of(cd / "harmonics_A.npz", *chosen, H=1))]
    others += [(f"mu {mu:g}, kn {kn:g}, kt/kn {r:g}", curve_of(cd / "coarse.npz", mu, kn, r))
               for mu, kn, r in study["example_curves"]]
    return [cv for cv in curves if cv[1] is not None], [cv for cv in others if cv[1] is not None]
