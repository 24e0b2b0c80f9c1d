"""Contact variety of the reference rings, and the search over the model's free parameters.

The paper (Sun et al. 2022, §3.1.2, Figs. 6, 11, 19) finds that the ring's shape changes *which*
pairs touch and how the normal preload N0 is distributed, not only its size. This study measures
that on the static contact state (``static.nc``) of seven reference rings (:data:`REFERENCE_RINGS`)
and scores it against the paper's description row by row (:data:`PAPER_ROWS`, :func:`score`).

Metric of one ring (:func:`contact_variety`), with s = θ / θ_h ∈ [−1, 1] the pair's angle over the
sector half angle (s = 0 under the blade, |s| = 1 on the sector boundaries):

* open fraction: pairs with N0 = 0 (the static state is exactly complementary);
* where the gaps are: the gap-weighted mean of |s|, the largest gap in the central third
  (|s| ≤ 1/3) and in the outer third (|s| ≥ 2/3);
* how concentrated N0 is: peak / mean contact pressure, the pressure of a θ station being the
  N0 of its pairs (all axial positions) over their tributary area (the consistent nodal areas of the
  27-node faces alternate along z; summed per station they give the pressure resultant), the mean
  ΣN0 / Σarea; the N0-weighted mean of |s| (its centre of mass in θ: 0 centre, 1/2 uniform,
  1 boundary); and |s| of the peak pressure.

The search (:func:`search`) varies the free parameters that move the static state: the ring's
nominal radial clearance at rest (``geometry.ring.radial_clearance``; negative: an interference fit,
the ring pressed into the groove at rest), the normal contact stiffness per area (kt kept at the
configured kt/kn) and the groove support, the rim arm's radial thickness and axial length (the ring
moves with the arm's centre, :func:`ringdamper.config.ring_axial_center`).
μ and kt do not move the static state; they and the clearance move the default ring's backbone,
charted by :func:`backbone_sweep` with ``studies.contact_calibration``'s metrics. :func:`free_closure`
gives the closure of every pair when the clearance exceeds the ring's growth (no pair touches): how
far the ring would enter the groove, i.e. what the contact has to absorb, station by station.
"""

from __future__ import annotations

import copy
import itertools
from dataclasses import asdict, dataclass

import numpy as np
import xarray as xr

from ringdamper.campaign import design_space
from ringdamper.config import ring_axial_center
from ringdamper.static.closure import pair_closure, station_means
from ringdamper.static.surface import sector_position

# the paper's seven rings of Figs. 6, 11, 19 (the campaign's reference rings but kappa3 = +1)
REFERENCE_RINGS = {label: k for label, k in design_space.REFERENCE_RINGS.items() if label != "kappa3=+1"}
PAPER_ROWS = {
    "default": "N0 greatest at the centre; nodes near the sector boundaries open, with the largest gaps",
    "kappa1=+1": "more nodes in contact than the default; N0 more dispersed",
    "kappa1=-1": "more separated nodes with larger gaps than the default; N0 values similar",
    "kappa2=+1": "N0 concentrated in the middle; the largest boundary gaps of the seven rings",
    "kappa2=-1": "N0 more dispersed than the default",
    "kappa3=-1": "the highest N0 of the seven, under the blade; the largest gaps at the outer nodes",
    "paper optimum": "more nodes in contact, higher N0 and smaller gaps than the default",
}
CENTRE, OUTER = 1.0 / 3.0, 2.0 / 3.0   # |s| bounds of the central and outer thirds of the sector
SIMILAR = 0.25                          # "similar" N0: peak pressures within 25 %


@dataclass
class Variety:
    """Contact variety of one static state (gaps in m, pressures in Pa, positions in |s|)."""

    n_pairs: int
    open_fraction: float
    max_gap: float
    gap_position: float        # gap-weighted mean |s| (NaN without gap)
    centre_gap: float          # largest gap with |s| <= 1/3
    outer_gap: float           # largest gap with |s| >= 2/3
    peak_pressure: float      # of the θ stations
    mean_pressure: float
    concentration: float       # peak / mean pressure
    n0_position: float         # N0-weighted mean |s|
    peak_position: float       # |s| of the peak pressure


def _weighted_mean(x, w) -> float:
    total = float(np.sum(w))
    return float(np.sum(x * w) / total) if total > 0 else float("nan")


def contact_variety(static: xr.Dataset, half_angle: float) -> Variety:
    """:class:`Variety` of a ``static.nc`` dataset (pair positions x, y at rest, N0, gap, area) of a
    sector of half angle ``half_angle`` (rad) centred on the X axis."""
    s = sector_position(static, half_angle)
    n0, gap, area = static.N0.values, static.gap.values, static.area.values
    stations, station = np.unique(np.round(s, 9), return_inverse=True)
    p = np.bincount(station, n0) / np.bincount(station, area)
    mean_p = float(np.sum(n0) / np.sum(area))
    centre, outer = s <= CENTRE + 1e-9, s >= OUTER - 1e-9
    i = int(np.argmax(p))
    return Variety(n_pairs=int(s.size), open_fraction=float(np.mean(n0 == 0.0)),
                   max_gap=float(gap.max()), gap_position=_weighted_mean(s, gap),
                   centre_gap=float(gap[centre].max()), outer_gap=float(gap[outer].max()),
                   peak_pressure=float(p[i]), mean_pressure=mean_p,
                   concentration=float(p[i] / mean_p) if mean_p > 0 else float("nan"),
                   n0_position=_weighted_mean(s, n0), peak_position=float(stations[i]))


def score(v: dict[str, Variety]) -> dict[str, bool]:
    """Row-by-row verdict of the seven rings' varieties ``v`` (label of :data:`REFERENCE_RINGS` ->
    :class:`Variety`) against :data:`PAPER_ROWS`. "More/less" compares with the default ring;
    "centre" is |s| <= 1/3, "outer" |s| >= 2/3; "dispersed" is a lower peak/mean pressure."""
    d = v["default"]
    peak_all = max(x.peak_pressure for x in v.values())
    outer_all = max(x.outer_gap for x in v.values())
    k1p, k1m, k2p, k2m = v["kappa1=+1"], v["kappa1=-1"], v["kappa2=+1"], v["kappa2=-1"]
    k3m, opt = v["kappa3=-1"], v["paper optimum"]
    return {
        "default": bool(d.n0_position < 0.5 and d.peak_position <= CENTRE and d.open_fraction > 0
                        and d.outer_gap == d.max_gap),
        "kappa1=+1": bool(k1p.open_fraction < d.open_fraction and k1p.concentration < d.concentration),
        "kappa1=-1": bool(k1m.open_fraction > d.open_fraction and k1m.max_gap > d.max_gap
                          and abs(k1m.peak_pressure / d.peak_pressure - 1) <= SIMILAR),
        "kappa2=+1": bool(k2p.concentration > d.concentration and k2p.n0_position < 0.5
                          and k2p.peak_position <= CENTRE and k2p.outer_gap > 0
                          and k2p.outer_gap == outer_all),
        "kappa2=-1": bool(k2m.concentration < d.concentration),
        "kappa3=-1": bool(k3m.peak_pressure == peak_all and k3m.peak_position <= CENTRE
                          and k3m.outer_gap > 0 and k3m.outer_gap == k3m.max_gap),
        "paper optimum": bool(opt.open_fraction < d.open_fraction
                                  and opt.peak_pressure > d.peak_pressure and opt.max_gap < d.max_gap),
    }


SUPPORT = ("arm_thickness", "arm_length")   # the groove-support dials (geometry.disk)


def design_config(config: dict, design: dict) -> dict:
    """``config`` with the entries of ``design`` that it holds: ``radial_clearance`` (m),
    ``normal_stiffness_per_area`` (N/m³, kt at the same kt/kn), ``arm_thickness`` and ``arm_length``
    (m; the ring moves with the arm's centre)."""
    cfg = copy.deepcopy(config)
    g = cfg["geometry"]
    if "normal_stiffness_per_area" in design:
        c, kn = cfg["contact"], float(design["normal_stiffness_per_area"])
        ratio = c["tangential_stiffness_per_area"] / c["normal_stiffness_per_area"]
        c.update(normal_stiffness_per_area=kn, tangential_stiffness_per_area=ratio * kn)
    if "radial_clearance" in design:
        g["ring"]["radial_clearance"] = float(design["radial_clearance"])
    if "arm_length" in design:
        g["ring"]["axial_center"] = ring_axial_center(g, float(design["arm_length"]))
    g["disk"].update({k: float(design[k]) for k in SUPPORT if k in design})
    return cfg


def support_of(config: dict) -> dict:
    """The groove-support dials of ``config`` (:data:`SUPPORT`)."""
    return {k: float(config["geometry"]["disk"][k]) for k in SUPPORT}


def configured_design(config: dict) -> dict:
    """The model's own design: its radial clearance, kn per area and groove support."""
    return {"radial_clearance": config["geometry"]["ring"]["radial_clearance"],
            "normal_stiffness_per_area": config["contact"]["normal_stiffness_per_area"], **support_of(config)}


def support_label(support: dict) -> str:
    """``arm <thickness> x <length> mm`` of a groove support."""
    return f"arm {1e3 * support['arm_thickness']:g} x {1e3 * support['arm_length']:g} mm"


def sector_half_angle(config: dict) -> float:
    """The sector's half angle θ_h = π / N (rad)."""
    return np.pi / config["geometry"]["n_sectors"]


def _static_states(config: dict, kappa, designs) -> list[xr.Dataset]:
    """``static.nc`` datasets of ring ``kappa`` for each (clearance, kn per area) of ``designs``,
    meshing and assembling the sector once (the groove support is ``config``'s)."""
    from ringdamper.fem.model import build_model
    from ringdamper.geometry.sector import build_sector
    from ringdamper.static.stage import clearance_gaps, solve_problem, static_dataset, static_problem

    model = build_model(build_sector(config, kappa), config)
    speed = config["operation"]["speed_rpm"]
    out, problems = [], {}
    for clearance, kn in designs:
        if kn not in problems:
            problems[kn] = static_problem(model, design_config(config, {"normal_stiffness_per_area": kn}),
                                          speed)
        prob = copy.copy(problems[kn])
        prob.g0 = clearance_gaps(model, clearance)
        result = solve_problem(prob, config["static"])
        if result.status != 0:
            raise RuntimeError(f"static solve failed for kappa={kappa}, clearance={clearance}, "
                               f"kn={kn}: {result.reason}")
        out.append(static_dataset(model, result, prob, kappa, speed))
    return out


def ring_states(config: dict, designs) -> dict[str, list[xr.Dataset]]:
    """Static states of the seven reference rings (label -> one dataset per (clearance, kn))."""
    return {label: _static_states(config, kappa, designs) for label, kappa in REFERENCE_RINGS.items()}


def search(config: dict) -> tuple[list[dict], list[dict]]:
    """The full grid of ``studies.contact_state`` (``arm_thickness`` × ``arm_length`` ×
    ``radial_clearance`` × ``normal_stiffness_per_area``): (one row per design and ring: the
    :class:`Variety` and the row verdict; one row per design: the number of the paper's rows
    reproduced). Each groove support is meshed once per ring; the contact designs re-solve it."""
    grid = config["studies"]["contact_state"]
    half_angle = sector_half_angle(config)
    designs = list(itertools.product(grid["radial_clearance"], grid["normal_stiffness_per_area"]))
    ring_rows, design_rows = [], []
    for thickness, length in itertools.product(grid["arm_thickness"], grid["arm_length"]):
        support = {"arm_thickness": float(thickness), "arm_length": float(length)}
        states = ring_states(design_config(config, support), designs)
        for j, (clearance, kn) in enumerate(designs):
            v = {label: contact_variety(states[label][j], half_angle) for label in REFERENCE_RINGS}
            ok = score(v)
            key = {**support, "radial_clearance": float(clearance), "normal_stiffness_per_area": float(kn)}
            ring_rows += [{**key, "ring": label, **asdict(v[label]), "reproduced": ok[label]}
                          for label in REFERENCE_RINGS]
            design_rows.append({**key, "rows_reproduced": int(sum(ok.values())),
                                **{f"ok {label}": ok[label] for label in REFERENCE_RINGS}})
    return ring_rows, design_rows


def best_design(design_rows: list[dict], config: dict) -> dict:
    """The design reproducing the most rows; among ties the cheapest change from ``config``: the
    clearance nearest the configured one, then the configured arm (thickness, then length, each by
    its relative change), then kn nearest (in log) to the configured one."""
    kn0 = config["contact"]["normal_stiffness_per_area"]
    c0, support0 = config["geometry"]["ring"]["radial_clearance"], support_of(config)
    return min(design_rows, key=lambda r: (-r["rows_reproduced"], abs(r["radial_clearance"] - c0),
                                           *(abs(r[k] / support0[k] - 1) for k in SUPPORT),
                                           abs(np.log(r["normal_stiffness_per_area"] / kn0))))


def design_states(config: dict, design: dict) -> dict[str, xr.Dataset]:
    """Static states of the seven rings for one design row (label -> static.nc dataset)."""
    cfg = design_config(config, {k: design[k] for k in SUPPORT})
    states = ring_states(cfg, [(design["radial_clearance"], design["normal_stiffness_per_area"])])
    return {label: ds[0] for label, ds in states.items()}


def free_closure(config: dict, clearance: float) -> tuple[xr.Dataset, xr.Dataset]:
    """Static state of the default ring with a clearance ``clearance`` above its growth relative to
    the groove: every pair open, and ``initial_gap - gap`` is the closure d_n each pair would need;
    with the :func:`underside_imprint` of the same solve."""
    from ringdamper.fem.model import build_model
    from ringdamper.geometry.sector import build_sector
    from ringdamper.static.stage import solve_static, static_dataset

    cfg = design_config(config, {"radial_clearance": clearance})
    model = build_model(build_sector(cfg, REFERENCE_RINGS["default"]), cfg)
    result, prob = solve_static(model, cfg)
    if result.status != 0 or np.any(result.in_contact):
        raise RuntimeError(f"clearance {clearance} m does not leave every pair open: {result.reason}, "
                           f"{int(np.sum(result.in_contact))} in contact")
    u = (prob.T @ result.u).reshape(-1, 3)
    return (static_dataset(model, result, prob, REFERENCE_RINGS["default"], cfg["operation"]["speed_rpm"]),
            underside_imprint(model, u, cfg["geometry"]["disk"]["contact_radius"]))


def closure_summary(static: xr.Dataset, half_angle: float) -> dict:
    """Of an all-open (:func:`free_closure`) state: the mean closure (the clearance at which the ring
    would just touch on average), the spread of the means of its axial stations (the arm's taper) and
    its sector-periodic part, the mean of the boundary station minus that of the centre station
    (> 0: the boundaries close more, so they carry N0 and the centre opens first). All in m."""
    s = sector_position(static, half_angle)
    closure = pair_closure(static)
    _, theta_means = station_means(static, s)
    _, z_means = station_means(static, static.z.values)
    return {"mean_closure": float(closure.mean()), "axial_spread": float(np.ptp(z_means)),
            "periodic_part": float(theta_means[-1] - theta_means[0])}


def closure_supports(config: dict) -> list[dict]:
    """The groove supports of the free-closure chart: the grid's ``arm_thickness`` × ``arm_length`` of
    ``studies.contact_state``, then the configured support when the grid does not hold it."""
    grid = config["studies"]["contact_state"]
    supports = [{"arm_thickness": t, "arm_length": length}
                for t, length in itertools.product(grid["arm_thickness"], grid["arm_length"])]
    return supports + [support_of(config)] * (support_of(config) not in supports)


def free_closures(config: dict) -> tuple[list[dict], dict]:
    """The :func:`free_closure` at ``studies.contact_state.free_clearance`` of every support of
    :func:`closure_supports`: (one row per support, the support and its :func:`closure_summary`;
    :func:`support_label` -> (static state, underside imprint))."""
    clearance = config["studies"]["contact_state"]["free_clearance"]
    closures = {support_label(s): (s, free_closure(design_config(config, s), clearance))
                for s in closure_supports(config)}
    rows = [{**s, **closure_summary(state, sector_half_angle(config))} for s, (state, _) in closures.values()]
    return rows, {label: c for label, (_, c) in closures.items()}


def underside_imprint(model, u: np.ndarray, radius: float) -> xr.Dataset:
    """Radial displacement of the blisk nodes on the cylinder r = ``radius`` (the rim's underside and,
    for the default ring, the groove), under the sector centre (the blade) and on its boundary, per
    axial position z: the sector-periodic part of the support's deformation is their difference."""
    from ringdamper.geometry.sector import BODY_RING, MERGE_TOL
    from ringdamper.io import variable

    x = model.nodes
    r = np.hypot(x[:, 0], x[:, 1])
    theta = np.abs(np.arctan2(x[:, 1], x[:, 0]))
    u_r = (u[:, 0] * x[:, 0] + u[:, 1] * x[:, 1]) / r
    on = np.flatnonzero((model.node_body != BODY_RING) & (np.abs(r - radius) < MERGE_TOL))
    zs = np.unique(np.round(x[on, 2], 9))
    centre, boundary = np.empty(zs.size), np.empty(zs.size)
    for k, z in enumerate(zs):
        plane = on[np.abs(x[on, 2] - z) < MERGE_TOL]
        centre[k], boundary[k] = u_r[plane[np.argmin(theta[plane])]], u_r[plane[np.argmax(theta[plane])]]
    return xr.Dataset({"centre": variable("z", centre, "m", "radial displacement under the blade"),
                       "boundary": variable("z", boundary, "m", "radial displacement on the sector boundary")},
                      coords={"z": variable("z", zs, "m", "axial position")})


def backbone_sweep(config: dict, reduced_path, target_hz: float) -> list[tuple[dict, dict]]:
    """Default-ring backbones (``contact_calibration.trial.run_trial``, its α grid) for each
    clearance of ``studies.contact_state.backbone_clearance`` at H = 1, with the configured contact
    and with each friction coefficient of ``backbone_friction``: [(row, curve)]. The reduced model is contact- and
    clearance-free, so the default ring's reduced.nc serves every trial."""
    from ringdamper.studies.contact_calibration.trial import DefaultRing, run_trial, trial_curve

    grid = config["studies"]["contact_state"]
    alpha = config["studies"]["contact_calibration"]["amplitudes"]
    out = []
    for clearance in grid["backbone_clearance"]:
        cfg = design_config(config, {"radial_clearance": clearance})
        ring = DefaultRing(cfg, reduced_path, target_hz)
        for mu in grid["backbone_friction"]:
            contact = dict(cfg["contact"], friction_coefficient=float(mu))
            row, ds = run_trial(ring, contact, 1, alpha)
            out.append(({"radial_clearance": float(clearance), **row}, trial_curve(ds)))
    return out
