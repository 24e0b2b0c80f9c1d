"""What raising the harmonic truncation of a converged EPMC point would change, without solving the
raised problem (docs/nonlinear_core.md §4.5).

A point ``z_H`` converged at ``H`` harmonics is padded with zero harmonics ``H+1 .. H'`` (``z₀``), the
raised residual ``r(z₀)`` and Jacobian ``J`` are evaluated at ``H'`` (AFT with the raised problem's
samples), and one Newton step of the raised system is taken. Partition the unknowns into the *old*
ones ``o`` (harmonics ``0..H`` of the contact slots and explicit modes, ω, ξ) and the *new* ones ``n``
(harmonics ``H+1..H'``). At ``z₀`` the old residual is the aliasing change of the AFT only and the new
one is the higher harmonics of the contact forces through the receptance. The step is

* ``"block"`` (the default): one block Gauss–Seidel sweep, new harmonics first,

      δ_n = −D_nn⁻¹ r_n,        δ_o = −J_oo⁻¹ (r_o + J_on δ_n),

  with ``D_nn`` the diagonal-in-harmonic blocks of ``J_nn`` (one small solve per new harmonic, of order
  ``2p + 2 s_h``: its cosine and sine contact slots and explicit modes) and ``J_oo`` the raised
  Jacobian's old block (the order of the point's own Newton system at ``H``);
* ``"newton"``: the full Newton step ``δ = −J⁻¹ r`` (one LU of the raised order).

The estimated change of each output is that of the E-EBM
(:func:`ringdamper.nonlinear.harmonic_balance.eebm.eebm`) of the stepped state ``z₀ + δ`` evaluated at
``H'`` against the point at ``H``: ω, ζ = ξ/2ω, γ, |q_res,z| (peak) and the modal amplitude
``(Q₁ᴴ M₁ Q₁)^½``, which the amplitude equation pins (its change measures how far the step leaves the
point's α).
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from ringdamper.nonlinear.harmonic_balance.condensed import CondensedHBM
from ringdamper.nonlinear.harmonic_balance.eebm import eebm
from ringdamper.nonlinear.harmonic_balance.epmc import (
    Backbone,
    EPMCProblem,
    _collect,
    _higher_model,
    _padded_state,
    _same_unknown,
)
from ringdamper.nonlinear.solvers.continuation import ContinuationPoint, NaturalResult
from ringdamper.nonlinear.solvers.jacobian import dense

#: the outputs whose relative change is estimated (keys of :attr:`HarmonicEstimate.change`)
ESTIMATED = ("omega", "zeta", "gamma", "q_res_peak", "amplitude")

#: the step rules of the module doc
METHODS = ("block", "newton")

#: ζ below which a point sticks (the value of :data:`ringdamper.nonlinear.adaptive.SLIP_ZETA`): the change
#: of ζ is relative to ``max(|ζ|, ZETA_FLOOR)``, so a stuck point (ζ = 0 to rounding) has a finite one
ZETA_FLOOR = 1e-9


@dataclass(frozen=True)
class HarmonicEstimate:
    """Estimated effect of raising point ``i`` from ``H`` to ``H_to``: ``change`` the relative change of
    each of :data:`ESTIMATED` (signed, new/old − 1), ``largest`` the largest of ω, ζ, γ and |q_res,z|
    (what :func:`ringdamper.nonlinear.adaptive.relative_change` measures between two solves),
    ``orders`` the orders of the systems solved (the LUs of the step) and ``seconds`` its wall time."""

    H: int
    H_to: int
    change: dict
    largest: float
    orders: tuple
    seconds: float


def point_outputs(backbone: Backbone, zeta_s: float) -> dict:
    """The estimated outputs (:data:`ESTIMATED`) of every point of ``backbone`` (arrays)."""
    res = eebm(backbone, zeta_s=zeta_s)
    amplitude = np.sqrt([np.sum(np.abs(e) ** 2) for e in backbone.eta[1]])
    return {"omega": res.omega, "zeta": res.zeta, "gamma": res.gamma, "q_res_peak": res.q_res_peak,
            "amplitude": amplitude}


def relative_changes(new: dict, old: dict) -> dict:
    """Signed relative change ``(new − old)/|old|`` of each of :data:`ESTIMATED` (ζ: over
    ``max(|old|, ZETA_FLOOR)``; inf where a value is not finite or an old one is zero)."""
    out = {}
    for k in ESTIMATED:
        scale = max(abs(float(old[k])), ZETA_FLOOR) if k == "zeta" else abs(float(old[k]))
        with np.errstate(divide="ignore", invalid="ignore"):
            c = (float(new[k]) - float(old[k])) / scale
        out[k] = c if np.isfinite(c) else np.inf
    return out


def new_unknowns(model: CondensedHBM, H: int) -> list:
    """Index arrays of the unknowns of each harmonic ``H+1 .. model.H`` of ``model`` (its cosine and
    sine contact slots, then its explicit modal coordinates)."""
    p = model.p
    return [np.r_[np.arange((2 * h - 1) * p, (2 * h + 1) * p),
                  np.arange(model.eta_slices[h].start, model.eta_slices[h].stop)]
            for h in range(H + 1, model.H + 1)]


def raised_step(J: np.ndarray, r: np.ndarray, blocks: list, method: str = "block") -> tuple[np.ndarray, tuple]:
    """The step ``δ`` of the module doc from the raised Jacobian ``J`` and residual ``r``, ``blocks`` the
    new unknowns per new harmonic (:func:`new_unknowns`), and the orders of the systems solved."""
    if method == "newton":
        return -np.linalg.solve(J, r), (J.shape[0],)
    new = np.concatenate(blocks)
    old = np.setdiff1d(np.arange(r.size), new)
    step = np.zeros_like(r)
    for b in blocks:
        step[b] = -np.linalg.solve(J[np.ix_(b, b)], r[b])
    step[old] = -np.linalg.solve(J[np.ix_(old, old)], r[old] + J[np.ix_(old, new)] @ step[new])
    return step, (old.size,) + tuple(b.size for b in blocks)


def estimate_raise(backbone: Backbone, i: int, H_to: int, nt: int, zeta_s: float, method: str = "block",
                   models: dict | None = None, current: dict | None = None) -> HarmonicEstimate:
    """Estimated change of point ``i`` of ``backbone`` raised to ``H_to`` harmonics (``nt`` AFT
    samples): module doc. ``models``: problems at higher truncations shared by the points, by
    ``(H, nt)`` (as :func:`ringdamper.nonlinear.harmonic_balance.epmc.resolve_point`); ``current``: the point's
    :func:`point_outputs` (one value each), computed when not given."""
    t0 = time.perf_counter()
    if method not in METHODS:
        raise ValueError(f"method: expected one of {METHODS}, got {method!r}")
    if not H_to > backbone.H:
        raise ValueError(f"H_to = {H_to}: must exceed the backbone's H = {backbone.H}")
    if H_to > backbone.model.structure.H_max:
        raise ValueError(f"H_to = {H_to} exceeds the {backbone.model.structure.H_max} harmonics of the structure")
    model = None if models is None else models.get((H_to, nt))
    if model is None:
        model = _higher_model(backbone, H_to, nt, (backbone.omega[i], backbone.xi[i]))
        if models is not None:
            models[H_to, nt] = model
    z0 = _padded_state(backbone, i, model)
    problem = EPMCProblem(model, _same_unknown(backbone.model, model, backbone.phase_index),
                          backbone.drift_tol, backbone.amplitude, gauge=model.gauge_at(z0, backbone.pinned[i]))
    s = float(np.log(backbone.alpha[i]))
    ev = problem.fun(z0, s)
    step, orders = raised_step(dense(ev.J), ev.r, new_unknowns(model, backbone.H), method)
    z1 = z0 + step
    stepped = problem.fun(z1, s, jacobian=False)
    run = NaturalResult(np.array([s]), [ContinuationPoint(s, z1, stepped.payload, 0)], np.zeros(1, int), [""], [])
    after = point_outputs(_collect(run, model, backbone.alpha[i:i + 1], problem, 0.0, backbone.pole_window), zeta_s)
    before = current if current is not None else {k: v[i] for k, v in point_outputs(backbone, zeta_s).items()}
    change = relative_changes({k: v[0] for k, v in after.items()}, before)
    largest = max(abs(change[k]) if np.isfinite(change[k]) else np.inf for k in ESTIMATED[:4])
    return HarmonicEstimate(backbone.H, H_to, change, largest, orders, time.perf_counter() - t0)
