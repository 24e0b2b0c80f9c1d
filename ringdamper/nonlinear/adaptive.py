"""Adaptive harmonic truncation along a backbone (docs/nonlinear_core.md §4.5).

The continuation runs at the base truncation H₀ over the whole amplitude grid. Then, point by
point, a usable grid point is solved again at H + 2 (:func:`_raise`) while

* its truncation indicator ε_H exceeds :data:`ringdamper.nonlinear.indicators.truncation.THRESHOLD`, or
* the point is *watched* and has not yet been seen to converge in H: at H₀, or where the largest
  relative change of ω, ζ, γ and |q_res,z| from the previous truncation exceeds
  :data:`CHANGE_TOLERANCE`. Watched are the points where preloaded pairs lift off during the period
  (``lifting_pairs > 0``, :mod:`ringdamper.nonlinear.indicators.separation`) and the slip onset: the first
  slipping point (ζ > :data:`SLIP_ZETA`) above a stuck one (preloaded pairs hold all period long and
  none slips), and each next slipping point while the one below moved by more than the tolerance
  from H₀ to H₀ + 2,

up to ``H_max``. Lift-off and slip onset have rules of their own because the highest-harmonic energy
can stay far below its threshold where H₀ is off: by 34 % in ζ at the default ring's top point, where
lift-off does not vanish as H grows (the clipped normal force feeds every harmonic), and by 2.7 % at its
first slipping point, where a short slip event of the period has harmonics that the displacements
hardly show (ε₃ = 7e-7). There the measure is how much the point moves.
A point whose indicators are quiet keeps H₀ and its continuation solution untouched. A raise has a
hard budget of LU factorisations (:mod:`ringdamper.nonlinear.solvers.budget`). A raise that fails, or
runs past its budget, stops there: the point keeps the last converged truncation, says so in its
reason, and gets a truncation flag (:data:`TRUNCATION_FLAGS`) and the estimated error of that
truncation (:func:`ringdamper.nonlinear.indicators.harmonic_estimate.estimate_raise` to H + 2). Every
output of a point (backbone, E-EBM, indicators, status) comes from its final truncation.
"""
from __future__ import annotations

import logging
from dataclasses import dataclass

import numpy as np

from ringdamper.nonlinear.contact.friction import FrictionContacts
from ringdamper.nonlinear.harmonic_balance.eebm import eebm
from ringdamper.nonlinear.harmonic_balance.epmc import Backbone, continue_point, resolve_point
from ringdamper.nonlinear.indicators.conditioning import backbone_conditions
from ringdamper.nonlinear.indicators.harmonic_estimate import estimate_raise
from ringdamper.nonlinear.indicators.separation import separation_indicators
from ringdamper.nonlinear.indicators.truncation import THRESHOLD, highest_harmonic_fraction
from ringdamper.nonlinear.solvers.budget import LUBudgetExceeded, lu_budget
from ringdamper.status import usable_status

log = logging.getLogger(__name__)

#: largest relative change of ω, ζ, γ and |q_res,z| between two truncations H − 2 and H at which a
#: lifting point counts as converged in H
CHANGE_TOLERANCE = 0.01

#: ζ above which a point slips. Measured over a campaign's 63 rings: |ζ| ≤ 8e-18 at the 1006 points below
#: the stick limit (zero to rounding), ζ ≥ 1.5e-8 at the 846 slipping ones
SLIP_ZETA = 1e-9

#: estimated largest change (:func:`ringdamper.nonlinear.indicators.harmonic_estimate.estimate_raise`, H to
#: H + 2) above which a watched point is raised when the estimate gates the raise (``adapt_harmonics(...,
#: estimate_flag=ESTIMATE_FLAG)``): :data:`CHANGE_TOLERANCE`/3. The estimate was 0.56–1.5× the solved
#: change wherever that exceeds 0.1 % on the default ring, the gap family and a one-DoF Jenkins oscillator
#: (docs/investigations/2026-12-02-harmonic-error-estimate.md)
ESTIMATE_FLAG = CHANGE_TOLERANCE / 3

#: Newton iterations (fresh Jacobians) of a higher-H solve before the next start is tried: on the default
#: ring the converging ones take at most 6
RAISE_MAX_ITER = 8

#: LU factorisations a raise of one point by 2 harmonics may make (``dnnm.raise_budget_lus``'s default):
#: above its two Newton starts (2 × :data:`RAISE_MAX_ITER`) and a continuation from the point below
#: at ``ARC_POINTS`` = 100 arc points of :mod:`ringdamper.nonlinear.stage`, a few LUs each
RAISE_BUDGET_LUS = 5000

#: values of a point's truncation flag (``truncation_flag`` of dnnm.nc)
TRUNCATION_FLAGS = {0: "converged in H or not raised", 1: "raise over its LU budget", 2: "raise failed"}

#: the outputs of a backbone point, per amplitude (arrays on the first axis)
OUTPUTS = ("omega", "frequency", "zeta", "gamma", "phi", "q_res_peak", "q_res_h1", "energy_dissipated",
           "e_damp", "drift", "highest_harmonic_energy", "normal_force_ratio_min", "lifting_pairs",
           "jacobian_condition", "status")


@dataclass
class AdaptiveResult:
    """Outputs of every grid point at its own truncation: ``values`` (the :data:`OUTPUTS` arrays),
    ``reason`` per point, ``n_harmonics`` the H each point was solved at, ``resolved`` the number of
    higher-H Newton solves, ``notes`` the points where one failed and ``estimated`` the number of
    error estimates (``estimate_flag``). ``values`` also holds ``truncation_flag``
    (:data:`TRUNCATION_FLAGS`) and ``truncation_error``: the estimated largest relative change of ω,
    ζ, γ and |q_res,z| from the kept H to H + 2 at a flagged point, NaN at the others."""

    values: dict
    reason: list
    n_harmonics: np.ndarray
    resolved: int
    notes: list
    estimated: int = 0


def backbone_outputs(backbone: Backbone, contacts: FrictionContacts, zeta_s: float) -> dict:
    """The :data:`OUTPUTS` of every point of ``backbone``: its E-EBM, drift, truncation and
    separation indicators, the condition number of its Newton Jacobian
    (:func:`ringdamper.nonlinear.indicators.conditioning.backbone_conditions`) and status."""
    res = eebm(backbone, zeta_s=zeta_s)
    n_min, lifting = separation_indicators(backbone, contacts, usable_status(res.status))
    return {"omega": res.omega, "frequency": res.frequency, "zeta": res.zeta, "gamma": res.gamma,
            "phi": res.phi, "q_res_peak": res.q_res_peak, "q_res_h1": res.q_res_h1,
            "energy_dissipated": res.energy_dissipated, "e_damp": res.e_damp, "drift": backbone.drift,
            "highest_harmonic_energy": highest_harmonic_fraction(backbone.model.modal, backbone.eta,
                                                                 backbone.omega),
            "normal_force_ratio_min": n_min, "lifting_pairs": lifting,
            "jacobian_condition": backbone_conditions(backbone), "status": np.asarray(res.status)}


def relative_change(new: dict, old: dict) -> float:
    """Largest relative change of ω, ζ, γ and |q_res,z| (peak) of one point from ``old`` to ``new``
    (inf where one is not finite or an old value is zero)."""
    keys = ("omega", "zeta", "gamma", "q_res_peak")
    with np.errstate(divide="ignore", invalid="ignore"):
        change = [abs(float(new[k]) / float(old[k]) - 1.0) for k in keys]
    return max(c if np.isfinite(c) else np.inf for c in change)


def needs_more_harmonics(point: dict, previous: dict | None, change_tol: float = CHANGE_TOLERANCE,
                         onset: bool = False) -> bool:
    """The rule of the module doc for one point (``previous``: the same point at H − 2, None at H₀;
    ``onset``: the point belongs to the slip onset)."""
    if not usable_status(point["status"]):
        return False
    if point["highest_harmonic_energy"] > THRESHOLD:
        return True
    if not (point["lifting_pairs"] > 0 or onset):
        return False
    return previous is None or relative_change(point, previous) > change_tol


def time_samples(H: int, base_H: int, base_nt: int) -> int:
    """AFT samples at ``H``: ``⌈base_nt · H / base_H⌉``, the base truncation's samples per harmonic.
    On the separating-contact study's gap family (docs/method_limits.md §2) the E-EBM amplitude at
    H = 5 is within 0.9 % of H = 11 with 32 samples per harmonic (160) and 1.5 % off with 128."""
    return -(-base_nt * H // base_H)


def _raise(current: Backbone, j: int, H: int, nt: int, tol: float, below: dict,
           alpha: float, max_arc_points: int | None, models: dict) -> tuple[Backbone | None, str]:
    """Point ``j`` of ``current`` at ``H`` (``below``: the grid point below, H -> (backbone, index),
    at the truncations it was solved at): Newton (at most :data:`RAISE_MAX_ITER` Jacobians) from its
    solution zero-padded; else from that plus the change raising H made to the point below; else
    continuation at ``H`` from the point below. Where many pairs lift off, the zero-padded start can
    be too far for Newton; the continuation is the robust and slow way (on the default ring 8–64 s
    against 0.5–4 s for Newton). ``models``: the problems at higher H built so far, shared by the
    points (:func:`ringdamper.nonlinear.harmonic_balance.epmc.resolve_point`)."""
    higher, why = resolve_point(current, j, H, nt, tol, RAISE_MAX_ITER, models=models)
    if higher is not None or H not in below:
        return higher, why
    if current.H in below:
        lower, k = below[current.H]
        higher, why_shift = resolve_point(current, j, H, nt, tol, RAISE_MAX_ITER,
                                          neighbour=(lower, k, below[H][0]), models=models)
        if higher is not None:
            return higher, ""
        why = f"{why}; shifted start: {why_shift}"
    higher, why_below = continue_point(below[H][0], below[H][1], alpha, tol, max_arc_points=max_arc_points)
    return higher, f"{why}; {why_below}" if higher is None else ""


def _bounded_raise(current: Backbone, j: int, H: int, nt: int, tol: float, below: dict, alpha: float,
                   max_arc_points: int | None, models: dict,
                   budget: int | None) -> tuple[Backbone | None, str, int]:
    """:func:`_raise` within an LU budget of ``budget`` factorisations: ``(higher, why, flag)``, ``flag``
    the point's :data:`TRUNCATION_FLAGS` value should it keep the lower truncation (1 over budget, 2
    failed)."""
    try:
        with lu_budget(budget):
            higher, why = _raise(current, j, H, nt, tol, below, alpha, max_arc_points, models)
    except LUBudgetExceeded as err:
        return None, f"raise to H = {H}: {err}", 1
    return higher, why, 2


def _kept_error(current: Backbone, j: int, H_to: int, nt: int, zeta_s: float, models: dict) -> float:
    """Estimated truncation error of point ``j`` of ``current`` at its H: the largest relative change
    :func:`ringdamper.nonlinear.indicators.harmonic_estimate.estimate_raise` gives for raising it to
    ``H_to`` (inf where the estimate's linear systems are singular)."""
    try:
        return float(estimate_raise(current, j, H_to, nt, zeta_s, models=models).largest)
    except np.linalg.LinAlgError:
        return np.inf


def adapt_harmonics(backbone: Backbone, contacts: FrictionContacts, H_max: int, zeta_s: float,
                    tol: float = 1e-8, change_tol: float = CHANGE_TOLERANCE,
                    max_arc_points: int | None = None, estimate_flag: float | None = None,
                    raise_budget_lus: int | None = RAISE_BUDGET_LUS) -> AdaptiveResult:
    """Every point of ``backbone`` at the truncation the rule of the module doc picks (H₀ = the
    backbone's, steps of 2 up to ``H_max``; the structure must hold harmonics up to ``H_max``;
    ``max_arc_points``: arc-length points a continuation at the higher H may take past a fold, as in
    :func:`ringdamper.nonlinear.harmonic_balance.epmc.epmc`). ``estimate_flag``: a watched point at H₀ is
    first estimated (:func:`ringdamper.nonlinear.indicators.harmonic_estimate.estimate_raise`, to H₀ + 2)
    and raised only if the estimated largest change exceeds this level; otherwise it keeps H₀ and its
    solution untouched, and the estimate stands for its change from H₀ to H₀ + 2 in the slip onset rule
    (None: no estimate). ``raise_budget_lus``: LU factorisations each raise may make (None: no limit)."""
    H0, nt0 = backbone.H, backbone.nt
    if H_max > backbone.model.structure.H_max:
        raise ValueError(f"H_max = {H_max} exceeds the {backbone.model.structure.H_max} harmonics of the "
                         "structure")
    values = backbone_outputs(backbone, contacts, zeta_s)
    values = {k: np.array(v, copy=True) for k, v in values.items()}
    values["truncation_flag"] = np.zeros(backbone.alpha.size, np.int8)
    values["truncation_error"] = np.full(backbone.alpha.size, np.nan)
    reason = list(backbone.reason)
    used = np.full(backbone.alpha.size, H0)
    notes, resolved, estimated = [], 0, 0
    below: dict = {}                    # H -> (backbone, index) of the grid point below, solved at H
    models: dict = {}                   # (H, nt) -> the problem at that truncation, built once
    usable = usable_status(values["status"])
    slipping = usable & (values["zeta"] > SLIP_ZETA)
    with np.errstate(invalid="ignore"):                 # stuck: preloaded pairs hold and none slips
        stuck = usable & ~slipping & (values["normal_force_ratio_min"] > 0)
    onset_open = False                  # the next slipping point belongs to the slip onset
    for i in range(backbone.alpha.size):
        current, j, H = backbone, i, H0
        point, previous, solved = {k: v[i] for k, v in values.items()}, None, {H0: (backbone, i)}
        onset = bool(slipping[i]) and onset_open
        first_change = 0.0
        while H + 2 <= H_max and needs_more_harmonics(point, previous, change_tol, onset):
            if estimate_flag is not None and H == H0 and point["highest_harmonic_energy"] <= THRESHOLD:
                first_change = estimate_raise(backbone, i, H + 2, time_samples(H + 2, H0, nt0), zeta_s,
                                              models=models).largest
                estimated += 1
                if first_change <= estimate_flag:
                    break
            nt = time_samples(H + 2, H0, nt0)
            higher, why, flag = _bounded_raise(current, j, H + 2, nt, tol, below, backbone.alpha[i],
                                               max_arc_points, models, raise_budget_lus)
            resolved += 1
            if higher is None:
                notes.append(f"alpha = {backbone.alpha[i]:.4g}: {why}; kept H = {H}")
                reason[i] = "; ".join(r for r in (reason[i], notes[-1]) if r)
                values["truncation_flag"][i] = flag
                values["truncation_error"][i] = _kept_error(current, j, H + 2, nt, zeta_s, models)
                break
            solved[H + 2] = (higher, 0)
            out = backbone_outputs(higher, contacts, zeta_s)
            previous, point = point, {k: v[0] for k, v in out.items()}
            if H == H0:
                first_change = relative_change(point, previous)
            current, j, H = higher, 0, H + 2
            if higher.reason[0]:
                reason[i] = higher.reason[0]
        for k in OUTPUTS:
            values[k][i] = point[k]
        used[i] = H
        below = solved
        if stuck[i] or slipping[i]:         # a point that is neither leaves the onset as it was
            onset_open = bool(stuck[i]) or (onset and first_change > change_tol)
    for note in notes:
        log.warning("adaptive harmonics: %s", note)
    return AdaptiveResult(values=values, reason=reason, n_harmonics=used, resolved=resolved, notes=notes,
                          estimated=estimated)
