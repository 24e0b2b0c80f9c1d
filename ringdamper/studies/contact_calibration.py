"""Calibration of the friction-contact parameters on the default ring (docs/design.md §2 "Contact pairs").

The paper does not give μ, kn, kt. They are chosen ONCE, on the default ring (κ = 0), inside the
physically plausible ranges of :data:`PLAUSIBLE`, so that the default ring's dNNM backbone resembles
the paper's §2.6 / Fig. 8 (:data:`PAPER_TARGET`): maximum modal damping ratio ζ_max ≈ 0.15 % at
|q_res,z| ≈ 0.164 mm, where the normalised resonant frequency has dropped from 2.195 to 2.187
(−0.36 %), with ζ → 0 and ω0 constant at small amplitude. They are never tuned per geometry.

Chain of one trial (:func:`run_trial`): the reduced model (contact-free, independent of the contact
parameters) is read once; the static contact state is re-solved for every trial (N0 depends on kn
through the penalty law), then the EPMC backbone + E-EBM of ``nonlinear.stage.run_dnnm`` on a fixed α
grid. Each backbone is summarised by :func:`backbone_metrics` and scored by :func:`objective`:

    J = w_ζ ln²(ζ_max / 0.15 %) + w_q ln²(q* / 0.164 mm) + w_Δ ln²(Δ* / 0.364 %) + P_shape,

all taken on the window |q_res,z| ≤ :data:`Q_MAX` = 0.45 mm (the paper's largest default-ring
amplitude), with ζ_max and q* = |q_res,z| at ζ_max refined by a parabola through the discrete peak
in (ln q, ζ), Δ* = 1 − ω(q*)/ω_stuck the relative frequency drop at q*, weights 1, 1, 1 (a factor e
off on any one quantity costs 1), and P_shape = 10 per violated shape rule (:data:`SHAPE_RULES`):
the frequency must not rise above the stuck frequency by more than 0.05 %, the damping peak must be
inside the window (not at its last point), and at least 80 % of the grid points must be usable
(status 0 or 3). The study (:func:`run_stage`, rules of ``make studies``, docs/calibration.md): a
coarse grid over (μ, kn, kt/kn) at H = 1, a refined grid around the best coarse row, then the chosen
set (``contact:`` of the configuration) and the runner-up at several H (harmonic truncation). The
grids, the α grid and the runner-up are the ``studies.contact_calibration`` section of the
configuration.
"""

from __future__ import annotations

import copy
import itertools
import time
from dataclasses import asdict, dataclass, field

import numpy as np

from ringdamper.nonlinear.normalisation import PAPER_NORMALISED_FREQUENCY, normalised_frequency
from ringdamper.status import usable_status

# Paper §2.6 / Fig. 8 on the default geometry.
PAPER_TARGET = {"zeta_max": 0.15e-2,                 # maximum modal damping ratio
                "q_at_zeta_max": 0.164e-3,           # |q_res,z| (m) at ζ_max
                "drop_at_zeta_max": 1 - 2.187 / PAPER_NORMALISED_FREQUENCY}   # 1 − ω0(ζ_max)/ω0(0) = 0.364 %
WEIGHTS = {"zeta_max": 1.0, "q_at_zeta_max": 1.0, "drop_at_zeta_max": 1.0}
SHAPE_PENALTY = 10.0
SHAPE_RULES = {"max_rise": 5e-4,        # ω/ω_stuck − 1 may not exceed this anywhere on the backbone
               "min_usable": 0.8}       # fraction of grid points with status 0 or 3

# Physically plausible ranges (docs/calibration.md gives the reasons and references).
PLAUSIBLE = {
    "friction_coefficient": (0.2, 0.8),              # dry Ti–Ti / Ti-6Al-4V, run-in fretting contacts
    "normal_stiffness_per_area": (1.0e10, 1.0e12),   # N/m^3 at ~0.1–1 MPa nominal pressure
    "tangential_stiffness_per_area": (5.0e9, 1.0e12),
    "kt_over_kn": (0.5, 1.0),                        # Mindlin (elastic spheres): 2(1−ν)/(2−ν) = 0.80
}

# α grid of the study (kg^0.5 m): |q_res,z| from ~5e-3 mm to ~0.9 mm on the default ring.
Q_MAX = 0.45e-3   # m: the metrics look at |q_res,z| <= 0.45 mm (paper Table 3: up to 0.44 mm)


@dataclass
class Metrics:
    """Summary of one backbone (q in m, drops and ζ as fractions)."""

    zeta_max: float
    q_at_zeta_max: float
    drop_at_zeta_max: float
    drop_final: float               # 1 − ω/ω_stuck at the last usable point
    max_rise: float                 # max(ω/ω_stuck − 1)
    q_onset: float                  # first |q| where ζ exceeds 1 % of ζ_max
    n_peaks: int                    # local maxima of ζ above 20 % of ζ_max
    peak_inside: bool               # ζ_max not at the last usable point
    usable_fraction: float
    status_counts: list = field(default_factory=list)   # counts of status 0..4 (others last)
    zeta_max_all: float = float("nan")                  # max ζ over the whole α grid
    q_at_zeta_max_all: float = float("nan")

    def row(self) -> dict:
        d = asdict(self)
        d["status_counts"] = " ".join(str(c) for c in self.status_counts)
        return d


def _peak(logq: np.ndarray, z: np.ndarray, i: int) -> tuple[float, float]:
    """Vertex of the parabola through points i−1, i, i+1 of (ln q, ζ) (the discrete peak at the ends)."""
    if i == 0 or i == len(z) - 1:
        return float(np.exp(logq[i])), float(z[i])
    x, y = logq[i - 1:i + 2], z[i - 1:i + 2]
    a, b, c = np.polyfit(x - x[1], y, 2)
    if a >= 0:
        return float(np.exp(logq[i])), float(z[i])
    xv = float(np.clip(-b / (2 * a), x[0] - x[1], x[2] - x[1]))
    return float(np.exp(x[1] + xv)), float(c - b * b / (4 * a))


def backbone_metrics(q, omega, zeta, status, omega_stuck: float, q_max: float = None) -> Metrics:
    """Summarise a backbone given per grid point |q_res,z| (m), ω (rad/s), ζ and status; the
    peak, drop and shape rules are taken over |q_res,z| ≤ ``q_max`` (default :data:`Q_MAX`), the
    largest default-ring amplitude of the paper (Table 3); ``zeta_max_all``/``q_at_zeta_max_all``
    give the maximum over the whole grid."""
    q_max = Q_MAX if q_max is None else q_max
    q, omega, zeta = (np.asarray(v, float) for v in (q, omega, zeta))
    status = np.asarray(status, int)
    counts = np.bincount(np.clip(status, 0, 5), minlength=6).tolist()
    ok = usable_status(status) & np.isfinite(q) & np.isfinite(omega) & np.isfinite(zeta) & (q > 0)
    if ok.sum() < 3:
        nan = float("nan")
        return Metrics(nan, nan, nan, nan, nan, nan, 0, False, float(ok.mean()), counts, nan, nan)
    q, omega, zeta = q[ok], omega[ok], zeta[ok]
    j = int(np.argmax(zeta))
    z_all, q_all = float(zeta[j]), float(q[j])
    inside = q <= q_max
    if inside.sum() < 3:
        nan = float("nan")
        return Metrics(nan, nan, nan, nan, nan, nan, 0, False, float(ok.mean()), counts, z_all, q_all)
    q, omega, zeta = q[inside], omega[inside], zeta[inside]
    order = np.argsort(q)
    q, omega, zeta = q[order], omega[order], zeta[order]
    logq = np.log(q)
    i = int(np.argmax(zeta))
    q_star, z_star = _peak(logq, zeta, i)
    ratio = omega / omega_stuck
    drop_star = 1.0 - float(np.interp(np.log(q_star), logq, ratio))
    above = np.flatnonzero(zeta > 0.01 * zeta[i])
    q_onset = float(q[above[0]]) if above.size else float("nan")
    inner = (zeta[1:-1] > zeta[:-2]) & (zeta[1:-1] >= zeta[2:]) & (zeta[1:-1] > 0.2 * zeta[i])
    n_peaks = int(inner.sum()) + int(zeta[-1] > zeta[-2] and zeta[-1] > 0.2 * zeta[i])
    return Metrics(zeta_max=z_star, q_at_zeta_max=q_star, drop_at_zeta_max=drop_star,
                   drop_final=1.0 - float(ratio[-1]), max_rise=float(np.max(ratio) - 1.0),
                   q_onset=q_onset, n_peaks=n_peaks, peak_inside=bool(i < len(zeta) - 1),
                   usable_fraction=float(ok.mean()), status_counts=counts,
                   zeta_max_all=z_all, q_at_zeta_max_all=q_all)


def objective(m: Metrics, target: dict = PAPER_TARGET, weights: dict = WEIGHTS) -> float:
    """J = Σ_k w_k ln²(m_k / target_k) + 10 × (number of violated shape rules); inf if undefined."""
    values = {k: getattr(m, k) for k in target}
    if not all(np.isfinite(v) and v > 0 for v in values.values()):
        return float("inf")
    fit = sum(weights[k] * np.log(values[k] / target[k]) ** 2 for k in target)
    return float(fit + SHAPE_PENALTY * shape_violations(m))


def shape_violations(m: Metrics) -> int:
    """Number of violated :data:`SHAPE_RULES` (frequency rise, peak outside the grid, failures)."""
    return (int(not m.max_rise <= SHAPE_RULES["max_rise"]) + int(not m.peak_inside)
            + int(not m.usable_fraction >= SHAPE_RULES["min_usable"]))


def contact_section(mu: float, kn_area: float, kt_over_kn: float) -> dict:
    """The ``contact:`` section of a trial."""
    return {"friction_coefficient": float(mu), "normal_stiffness_per_area": float(kn_area),
            "tangential_stiffness_per_area": float(kt_over_kn * kn_area)}


def in_plausible_range(contact: dict) -> bool:
    """Whether a ``contact:`` section lies inside :data:`PLAUSIBLE`."""
    vals = dict(contact, kt_over_kn=contact["tangential_stiffness_per_area"]
                / contact["normal_stiffness_per_area"])
    return all(lo * (1 - 1e-12) <= vals[k] <= hi * (1 + 1e-12) for k, (lo, hi) in PLAUSIBLE.items())


class DefaultRing:
    """The default ring's inputs, loaded once: sector model, reduced model, target frequency."""

    def __init__(self, config: dict, reduced_path: str, target_hz: float):
        from ringdamper.fem.model import build_model
        from ringdamper.geometry.sector import build_sector
        from ringdamper.io import read_netcdf

        self.config = config
        self.model = build_model(build_sector(config, (0.0, 0.0, 0.0)), config)
        self.reduced = read_netcdf(reduced_path)
        self.target_hz = float(target_hz)

    def static(self, contact: dict):
        """Static contact state (static.nc dataset) for the trial's contact parameters."""
        from ringdamper.static.stage import solve_static, static_dataset

        cfg = dict(self.config, contact=contact)
        result, prob = solve_static(self.model, cfg)
        if result.status != 0:
            raise RuntimeError(f"static solve failed: {result.reason}")
        return static_dataset(self.model, result, prob, (0.0, 0.0, 0.0), cfg["operation"]["speed_rpm"])


def run_trial(ring: DefaultRing, contact: dict, H: int, alpha, nt: int | None = None):
    """One backbone of the default ring on the α grid ``alpha`` = (first, last, count): returns
    (row dict, dnnm dataset)."""
    from ringdamper.nonlinear.stage import contacts_from_static, run_dnnm, structure_from_reduced, target_stuck_frequency

    t0 = time.perf_counter()
    cfg = copy.deepcopy(ring.config)
    cfg["contact"] = dict(contact)
    cfg["dnnm"].update(n_harmonics=int(H), amplitude_min=alpha[0], amplitude_max=alpha[1],
                       n_amplitudes=int(alpha[2]))
    if nt is not None:
        cfg["dnnm"]["n_time_samples"] = int(nt)
    static = ring.static(cfg["contact"])
    contacts = contacts_from_static(static, cfg["contact"], cfg["dnnm"]["friction_law"])
    w_stuck = target_stuck_frequency(structure_from_reduced(ring.reduced, 1), contacts, ring.target_hz)
    ds = run_dnnm(ring.reduced, static, cfg, ring.target_hz, w_stuck)
    m = backbone_metrics(ds.q_res_z.values, 2 * np.pi * ds.frequency.values, ds.zeta.values,
                         ds.status.values, w_stuck)
    row = {"H": int(H), **{k: contact[k] for k in contact},
           "kt_over_kn": contact["tangential_stiffness_per_area"] / contact["normal_stiffness_per_area"],
           "stuck_hz": w_stuck / (2 * np.pi), "n_in_contact": int(static.attrs["n_in_contact"]),
           "mean_pressure_pa": float(np.sum(static.N0.values) / np.sum(static.area.values)),
           **m.row(), "objective": objective(m), "shape_violations": shape_violations(m),
           "wall_s": time.perf_counter() - t0}
    return row, ds


_RING: DefaultRing | None = None


def _init_worker(config, reduced_path, target_hz):
    global _RING
    _RING = DefaultRing(config, reduced_path, target_hz)


def _worker(args):
    contact, H, alpha = args
    try:
        row, ds = run_trial(_RING, contact, H, alpha)
        curve = {"alpha": ds.amplitude.values, "q": ds.q_res_z.values,
                 "omega0": normalised_frequency(2 * np.pi * ds.frequency.values, ds.attrs["omega_stuck"]),
                 "zeta": ds.zeta.values, "gamma": ds.gamma.values, "status": ds.status.values}
    except Exception as err:  # a failing trial is a result of the study, not a crash of it
        row = {"H": H, **contact, "objective": float("inf"), "error": f"{type(err).__name__}: {err}"}
        curve = None
    return row, curve


def run_many(config, reduced_path, target_hz, trials, alpha, processes=2):
    """``trials`` = [(contact section, H)] in ``processes`` worker processes (each loads the default
    ring once); returns ``[(row, curve)]`` in the order of ``trials``."""
    import multiprocessing as mp

    jobs = [(c, H, tuple(alpha)) for c, H in trials]
    init = (config, reduced_path, target_hz)
    if processes <= 1:
        _init_worker(*init)
        return [_worker(j) for j in jobs]
    with mp.get_context("spawn").Pool(processes, initializer=_init_worker, initargs=init) as pool:
        return pool.map(_worker, jobs, chunksize=1)


def grid_contacts(grid: dict) -> list[dict]:
    """Every ``contact:`` section of a grid over (μ, kn per area, kt/kn), inside :data:`PLAUSIBLE`."""
    return [c for c in (contact_section(mu, kn, r) for mu, kn, r in itertools.product(
        grid["friction_coefficient"], grid["normal_stiffness_per_area"], grid["kt_over_kn"]))
        if in_plausible_range(c)]


STAGES = ("coarse", "refine", "harmonics_A", "harmonics_B")


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
    """All trials of ``stage`` (:func:`stage_trials`) on the study's α grid: ``[(row, curve)]``."""
    alpha = config["studies"]["contact_calibration"]["amplitudes"]
    return run_many(config, reduced_path, target_hz, stage_trials(config, stage), alpha, processes)


def contact_states(backbone, contacts) -> dict:
    """Per grid point of an EPMC ``backbone``: number of pairs that slip (|T_j| reaches μN in some
    direction during the period), that open (N = 0 at some sample), and the mean-free ring drift."""
    from ringdamper.nonlinear.friction import contact_aft

    model = backbone.model
    n = backbone.alpha.size
    out = {k: np.full(n, -1) for k in ("n_slip", "n_slip_t1", "n_slip_t2", "n_open", "n_fully_open")}
    for i in range(n):
        if not np.isfinite(backbone.omega[i]):
            continue
        d = backbone.d[i].reshape(model.C, model.npairs, 3).transpose(1, 2, 0)
        aft = contact_aft(contacts, model.fourier, d, jacobian=False)
        N, T = aft.normal, aft.tangential                      # (np, Nt), (np, 2, Nt)
        limit = contacts.mu[:, None] * N
        slip_dir = np.any((np.abs(T) >= limit[:, None, :] * (1 - 1e-9)) & (N[:, None, :] > 0), axis=2)
        slip = np.any(slip_dir, axis=1)
        opened = np.any(N <= 0, axis=1)
        out["n_slip"][i] = int(slip.sum())
        out["n_slip_t1"][i], out["n_slip_t2"][i] = (int(v) for v in slip_dir.sum(axis=0))
        out["n_open"][i] = int(opened.sum())
        out["n_fully_open"][i] = int(np.all(N <= 0, axis=1).sum())
    return out


def diagnose(ring: DefaultRing, contact: dict, H: int, alpha):
    """EPMC backbone of the default ring with per-point contact states (for the study's figures)."""
    from ringdamper.nonlinear.stage import contacts_from_static, structure_from_reduced, target_stuck_frequency
    from ringdamper.nonlinear.eebm import eebm
    from ringdamper.nonlinear.epmc import epmc

    cfg = ring.config["dnnm"]
    static = ring.static(contact)
    contacts = contacts_from_static(static, contact, cfg["friction_law"])
    structure = structure_from_reduced(ring.reduced, H)
    w_stuck = target_stuck_frequency(structure, contacts, ring.target_hz)
    a = np.geomspace(*alpha[:2], int(alpha[2]))
    bb = epmc(structure, contacts, a, H=H, nt=max(cfg["n_time_samples"], 16 * H),
              omega_target=w_stuck)
    res = eebm(bb, zeta_s=cfg["structural_damping_ratio"])
    return bb, res, contact_states(bb, contacts), w_stuck


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




def plot_backbones(curves: list[tuple[str, dict]], path, q_max: float = 1.0e-3) -> None:
    """Fig. 8-like figure: ω0, ζ, γ against |q_res,z| for labelled curves (first one bold), with
    the paper's §2.6 point (ζ_max 0.15 % at 0.164 mm, ω0 2.187) marked."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 3, figsize=(11, 4.0), dpi=90)
    for k, (label, c) in enumerate(curves):
        ok = usable_status(c["status"]) & np.isfinite(c["q"]) & (c["q"] <= q_max)
        q = c["q"][ok] * 1e3
        style = dict(lw=2.2, color="k") if k == 0 else dict(lw=1.0)
        axes[0].plot(q, c["omega0"][ok], label=label, **style)
        axes[1].plot(q, 100 * c["zeta"][ok], **style)
        axes[2].plot(q, c["gamma"][ok], **style)
    axes[0].plot([0.164], [2.187], "r*", ms=10, label="paper §2.6")
    axes[1].plot([0.164], [0.15], "r*", ms=10)
    for ax, yl in zip(axes, (r"$\omega_0$ (normalised)", r"$\zeta$ (%)", r"$\gamma$ (N)")):
        ax.set_xlabel(r"$|q_{res,z}|$ (mm)")
        ax.set_ylabel(yl)
        ax.grid(alpha=0.3)
    axes[2].set_yscale("log")
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=4, fontsize=7, frameon=False)
    fig.tight_layout(rect=(0, 0.12, 1, 1))
    fig.savefig(path, dpi=90)
    plt.close(fig)


def curve_of(npz_path, mu: float, kn: float, ratio: float, H: int = 1) -> dict:
    """One backbone from a stage's .npz (see :func:`save_curves`), None if the stage lacks it."""
    d = np.load(npz_path)
    ok = (np.isclose(d["friction_coefficient"], mu) & np.isclose(d["normal_stiffness_per_area"], kn)
          & np.isclose(d["tangential_stiffness_per_area"], ratio * kn) & (d["H"] == H))
    if not ok.any():
        return None
    i = int(np.flatnonzero(ok)[0])
    return {k: d[k][i] for k in ("alpha", "q", "omega0", "zeta", "gamma", "status")}


def figures(config: dict, curves_dir, backbone_png, examples_png) -> None:
    """The study's figures: the chosen backbone (``contact:``) at each H of the study with its H = 1
    neighbours of the refinement grid (``backbone_png``), and the chosen H = 1 backbone against the
    ``example_curves`` of the coarse grid (``examples_png``)."""
    from pathlib import Path

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
    plot_backbones([cv for cv in curves if cv[1] is not None], backbone_png)
    others = [(f"{label}, H=1", curve_of(cd / "harmonics_A.npz", *chosen, H=1))]
    others += [(f"mu {mu:g}, kn {kn:g}, kt/kn {r:g}", curve_of(cd / "coarse.npz", mu, kn, r))
               for mu, kn, r in study["example_curves"]]
    plot_backbones([cv for cv in others if cv[1] is not None], examples_png)
