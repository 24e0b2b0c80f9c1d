"""Extended energy balance method (paper §2.5.3.2, Eqs. 5–6; Sun et al. 2021a; docs/design.md §3.4).

For every dNNM point (ω, ζ = ξ/2ω, modal coordinates ``η_{h,r}``), with the Fourier convention
``q(t) = Re Σ_h Q_h e^{ihωt}`` (:mod:`ringdamper.nonlinear.fourier`) and ``Q_h = Φ_h η_h``:

    E_damp = ∫_0^T q̇ᵀ (C + 2ζω M) q̇ dt = π ω Σ_{h≥1} h² Q_hᴴ (C_h + 2ζω M_h) Q_h
           = π ω Σ_h h² Σ_r (c_r + ξ) |η_{h,r}|²                     (Eq. 6; c_r modal damping),

with ``C`` the structural damping ``zeta_s`` when the backbone was computed without it (the campaign).
A backbone of a structure with its own damping already has it in ``ξ`` (the EPMC's negative damping
balances every dissipation, :mod:`ringdamper.nonlinear.harmonic_balance.epmc`), so there ``c_r = 0`` and ``zeta_s``
must be zero: adding it would count that damping twice.
    E_f(γ, φ) = ∫_0^T Re(γ e^{iφ} F̂ e^{iωt}) · q̇ dt = π γ Im(e^{iφ} Q_1ᴴ F̂)      (Eq. 5),

so ``max_φ E_f = π γ |Q_1ᴴ F̂|`` at ``φ = π/2 − arg(Q_1ᴴ F̂)`` and ``E_f = E_damp`` gives
``γ = E_damp / (π |Q_1ᴴ F̂|)``. ``φ`` is the phase of the forcing relative to the dNNM's phase
normalisation. The energy dissipated by each contact pair per cycle is
``∮ λ·ḋ = π Σ_h h (λa_h db_h − λb_h da_h)`` (:func:`ringdamper.nonlinear.contact.friction.dissipated_energy`).

Validity. The E-EBM places the resonance on the undamped-like backbone (phase resonance); the
forced peak drifts off it as the total damping grows. With the total damping ratio seen by the mode

    ζ_tot = E_damp / (2π ω² Σ_h h² Σ_r |η_{h,r}|²)      (= (c + ξ)/(2ω) for one mode at H = 1),

the amplitude error against the forced-response peak passes 5 % at ζ_tot ≈ 0.31 for structural
(viscous) damping, ≈ 0.125 for non-proportional friction damping on a two-DoF chain, and never (up
to ζ_tot = 0.67) for friction on a single DoF (docs/method_limits.md §1, measured by
:mod:`ringdamper.studies.method_limits.eebm_validity`). Points above ``zeta_limit`` (default
``ZETA_LIMIT`` = 0.1, below every crossing) are flagged (``valid`` False) and logged as a warning.
"""
from __future__ import annotations

import logging
from dataclasses import dataclass

import numpy as np

from ringdamper.nonlinear.contact.friction import dissipated_energy
from ringdamper.nonlinear.harmonic_balance.epmc import Backbone
from ringdamper.nonlinear.harmonic_balance.response import response_harmonics, time_peak

log = logging.getLogger(__name__)

#: total damping ratio ζ_tot above which the E-EBM resonant amplitude may be off by more than 5 %
#: (docs/method_limits.md §1)
ZETA_LIMIT = 0.1


@dataclass
class EEBMResult:
    """E-EBM outputs on the backbone's α grid: ``omega`` [rad/s], ``frequency`` [Hz], ``zeta``,
    ``gamma`` [N], ``phi`` [rad], ``q_res_peak`` (peak of the response DoF's time signal) and
    ``q_res_h1`` (its first-harmonic magnitude) [m], ``energy_dissipated`` [J] (α × pair),
    ``e_damp`` [J], the total damping ratio ``zeta_total`` and ``valid`` (``zeta_total`` within
    the validity limit, module doc), and the backbone ``status``/``reason``."""

    alpha: np.ndarray
    omega: np.ndarray
    frequency: np.ndarray
    zeta: np.ndarray
    gamma: np.ndarray
    phi: np.ndarray
    q_res_peak: np.ndarray
    q_res_h1: np.ndarray
    energy_dissipated: np.ndarray
    e_damp: np.ndarray
    zeta_total: np.ndarray
    valid: np.ndarray
    status: np.ndarray
    reason: list


def eebm(backbone: Backbone, zeta_s: float | np.ndarray = 0.0,
         zeta_limit: float = ZETA_LIMIT) -> EEBMResult:
    """Apply the E-EBM to every point of ``backbone`` with structural modal damping ratio
    ``zeta_s`` (a backbone of a damped structure has its damping in ξ already: ``zeta_s`` must be 0)
    and the structure's harmonic-1 forcing; points whose total damping ratio exceeds ``zeta_limit``
    are flagged and logged."""
    model = backbone.model
    n = backbone.alpha.size
    if model.damped and np.any(np.asarray(zeta_s) != 0):
        raise ValueError("zeta_s: the backbone's structure has its own damping (C or modal ratios), "
                         "which the EPMC's xi already balances; give one of the two, not both")
    c = [np.zeros(m.w2.size) if model.damped else m.damping(zeta_s) for m in model.modal]
    f1 = model.modal[1].f
    if not np.any(f1):
        raise ValueError("the structure has no harmonic-1 forcing vector")
    gamma, phi, e_damp = np.full(n, np.nan), np.full(n, np.nan), np.full(n, np.nan)
    q_peak, q_h1, zeta_tot = np.full(n, np.nan), np.full(n, np.nan), np.full(n, np.nan)
    e_d = np.full((n, model.npairs), np.nan)
    for i in range(n):
        if not np.isfinite(backbone.omega[i]):
            continue
        w, xi = backbone.omega[i], backbone.xi[i]
        eta = [e[i] for e in backbone.eta]
        e_damp[i] = np.pi * w * sum(h * h * np.sum((c[h] + xi) * np.abs(eta[h]) ** 2)
                                    for h in range(1, model.H + 1))
        zeta_tot[i] = e_damp[i] / (2 * np.pi * w * w * sum(
            h * h * np.sum(np.abs(eta[h]) ** 2) for h in range(1, model.H + 1)))
        qf = np.vdot(eta[1], f1)                         # Q_1ᴴ F̂ = η_1ᴴ Φ_1ᴴ F̂
        gamma[i] = e_damp[i] / (np.pi * abs(qf))
        phi[i] = np.angle(np.exp(1j * (np.pi / 2 - np.angle(qf))))
        q = response_harmonics(model.modal, eta)
        q_h1[i], q_peak[i] = abs(q[1]), time_peak(q)
        d = backbone.d[i].reshape(model.C, model.npairs, 3).transpose(1, 2, 0)
        lam = backbone.lam[i].reshape(model.C, model.npairs, 3).transpose(1, 2, 0)
        e_d[i] = dissipated_energy(d, lam)
    valid = ~(zeta_tot > zeta_limit)
    if not valid.all():
        log.warning("E-EBM outside its validity range at %d of %d points: total damping ratio up to "
                    "%.3g > %.3g, the resonant amplitude may be off by more than 5 %% (compute the "
                    "forced response there)", int((~valid).sum()), n, np.nanmax(zeta_tot), zeta_limit)
    return EEBMResult(alpha=backbone.alpha, omega=backbone.omega,
                      frequency=backbone.omega / (2 * np.pi), zeta=backbone.zeta, gamma=gamma,
                      phi=phi, q_res_peak=q_peak, q_res_h1=q_h1, energy_dissipated=e_d,
                      e_damp=e_damp, zeta_total=zeta_tot, valid=valid, status=backbone.status,
                      reason=backbone.reason)
