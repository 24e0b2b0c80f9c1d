"""What a trial of the contact calibration measures: the summary of its backbone
(:func:`backbone_metrics`) and its score against the paper's default ring (:func:`objective`).

    J = w_ζ ln²(ζ_max / 0.15 %) + w_q ln²(q* / 0.164 mm) + w_Δ ln²(Δ* / 0.364 %) + P_shape,

all taken on the window |q_res,z| ≤ :data:`Q_MAX` = 0.45 mm (the paper's largest default-ring
amplitude), with ζ_max and q* = |q_res,z| at ζ_max interpolated in ln q
(:func:`ringdamper.campaign.summary.log_q_zeta_max`), Δ* = 1 − ω(q*)/ω_stuck the relative frequency
drop at q*, weights 1, 1, 1 (a factor e off on any one quantity costs 1), and P_shape = 10 per
violated shape rule (:data:`SHAPE_RULES`): the frequency must not rise above the stuck frequency by
more than 0.05 %, the damping peak must be inside the window (not at its last point), and at least
80 % of the grid points must be usable (status 0 or 3).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field

import numpy as np

from ringdamper.campaign.summary import grid_zeta_max, log_q_zeta_max
from ringdamper.nonlinear.normalisation import PAPER_NORMALISED_FREQUENCY
from ringdamper.status import usable_status

# Paper §2.6 / Fig. 8 on the default geometry.
PAPER_TARGET = {"zeta_max": 0.15e-2,                 # maximum modal damping ratio
                "q_at_zeta_max": 0.164e-3,           # |q_res,z| (m) at ζ_max
                "drop_at_zeta_max": 1 - 2.187 / PAPER_NORMALISED_FREQUENCY}   # 1 − ω0(ζ_max)/ω0(0) = 0.364 %
WEIGHTS = {"zeta_max": 1.0, "q_at_zeta_max": 1.0, "drop_at_zeta_max": 1.0}
SHAPE_PENALTY = 10.0
SHAPE_RULES = {"max_rise": 5e-4,        # ω/ω_stuck − 1 may not exceed this anywhere on the backbone
               "min_usable": 0.8}       # fraction of grid points with status 0 or 3

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
    z_all, j = grid_zeta_max(q, zeta)
    z_all, q_all = float(z_all), float(q[j])
    inside = q <= q_max
    if inside.sum() < 3:
        nan = float("nan")
        return Metrics(nan, nan, nan, nan, nan, nan, 0, False, float(ok.mean()), counts, z_all, q_all)
    q, omega, zeta = q[inside], omega[inside], zeta[inside]
    order = np.argsort(q)
    q, omega, zeta = q[order], omega[order], zeta[order]
    logq = np.log(q)
    i = int(np.argmax(zeta))
    q_star, z_star = log_q_zeta_max(q, zeta)
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
