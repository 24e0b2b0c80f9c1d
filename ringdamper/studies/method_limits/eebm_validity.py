"""E-EBM against the forced response as the damping grows (docs/method_limits.md §1).

Systems (unit masses and ground stiffness, so the linear modes are O(1) rad/s), each with Jenkins
elements of stiffness ``kt = ratio·k`` and slip limit ``μN = kt·a_s`` (slip amplitude ``a_s``):

* ``structural``: one DoF whose element never slips (μN huge), ``c = 2ζ_s ω_r`` with ζ_s growing —
  a linear oscillator, where the E-EBM's error is ``√(1 − ζ²) − 1`` exactly (the viscous force grows
  with frequency and the forced peak moves below the backbone's ω);
* ``friction_1dof``: one DoF, ζ_s = 1e-3, the forcing placing the resonance at ``a/a_s ∈ [1.5, 30]``
  for several stiffness ratios (the larger ``kt/k``, the larger the friction damping ratio);
* ``friction_2dof``: the chain ground–m1–m2 (``K = [[2, −1], [−1, 1]]``), the element between m2
  and the ground, forced and observed on m1: friction damping that is not proportional, so the
  forced response leaves the single nonlinear mode the E-EBM assumes.

For every case the E-EBM prediction (first backbone point at the forcing, as the campaign reads it,
:meth:`ringdamper.campaign.forced_check.EEBMBackbone.at_forcing`) is compared with the peak of the
forced response traced by arc length around it (:func:`ringdamper.nonlinear.harmonic_balance.frf.forced_response`,
:func:`~ringdamper.nonlinear.harmonic_balance.frf.resonance_peak`), against the total damping ratio ζ_tot of the
E-EBM point (:mod:`ringdamper.nonlinear.harmonic_balance.eebm`).
"""
from __future__ import annotations

import numpy as np
import xarray as xr

from ringdamper.campaign.forced_check import EEBMBackbone
from ringdamper.io import variable
from ringdamper.nonlinear.contact.friction import FrictionContacts
from ringdamper.nonlinear.harmonic_balance.eebm import eebm
from ringdamper.nonlinear.harmonic_balance.epmc import epmc
from ringdamper.nonlinear.harmonic_balance.frf import forced_response, resonance_peak
from ringdamper.nonlinear.harmonic_balance.structure import Structure

SLIP_AMPLITUDE = 0.01   # a_s [m]
H, NT = 1, 256


def jenkins_oscillator(ratio: float, slip: bool = True, dofs: int = 1, H: int = H):
    """The one-DoF oscillator or the two-DoF chain of the module doc with a Jenkins element
    ``kt = ratio`` (``slip`` False: a slip limit 1e6 times larger, never reached)."""
    K = np.eye(1) if dofs == 1 else np.array([[2.0, -1.0], [-1.0, 1.0]])
    B = np.zeros((3, dofs))
    B[1, -1] = 1.0
    e = np.eye(dofs)[0]
    st = Structure.real(np.eye(dofs), K, B, e, e, H=H)
    limit = ratio * SLIP_AMPLITUDE * (1.0 if slip else 1e6)
    return st, FrictionContacts(kn=1.0, kt=ratio, mu=limit, N0=1.0, gap=0.0)


def compare(structure, contacts, zeta_s: float, amplitudes) -> list[dict]:
    """E-EBM against the forced-response peak at the forcings whose E-EBM resonances lie at the
    modal ``amplitudes`` (increasing)."""
    grid = np.geomspace(0.3 * amplitudes[0], 1.2 * amplitudes[-1], 80)
    bb = epmc(structure, contacts, np.unique(np.r_[grid, amplitudes]), H=H, nt=NT, tol=1e-10)
    res = eebm(bb, zeta_s)
    backbone = EEBMBackbone.from_arrays(res.alpha, res.q_res_peak, res.gamma, res.omega, res.status)
    rows = []
    for a in amplitudes:
        k = int(np.argmin(np.abs(res.alpha - a)))
        gamma = res.gamma[k]
        if k >= backbone.alpha.size:                 # beyond the usable backbone: no prediction
            continue
        pred = backbone.at_forcing(gamma)
        half = min(0.6, max(0.05, 5 * res.zeta_total[k]))
        frf = forced_response(structure, contacts, gamma, (1 - half) * pred["omega"],
                              (1 + half) * pred["omega"], H=H, nt=NT, zeta_s=zeta_s, tol=1e-10,
                              stability=False)
        peak = resonance_peak(frf)
        rows.append({"zeta_total": res.zeta_total[k], "zeta_friction": res.zeta[k],
                     "eebm_amplitude": pred["q"], "frf_amplitude": peak.q_peak,
                     "error": pred["q"] / peak.q_peak - 1, "frf_status": frf.status,
                     "crossings": pred["crossings"]})
    return rows


def validity_study(zeta_structural=np.geomspace(0.01, 0.6, 12),
                   friction=(("friction_1dof", 1, (1.0, 10.0, 30.0)),
                             ("friction_2dof", 2, (1.0, 3.0, 10.0))),
                   slip_ratios=np.geomspace(1.5, 30.0, 6)) -> xr.Dataset:
    """Error of the E-EBM resonant amplitude against ζ_tot for every family (module doc);
    ``friction``: (family, DoFs, stiffness ratios)."""
    rows, family, ratio = [], [], []
    st, c = jenkins_oscillator(1.0, slip=False)
    for z in zeta_structural:
        rows += compare(st, c, float(z), [SLIP_AMPLITUDE])
        family.append("structural")
        ratio.append(1.0)
    for name, dofs, ratios in friction:
        for r in ratios:
            st, c = jenkins_oscillator(r, dofs=dofs)
            new = compare(st, c, 1e-3, SLIP_AMPLITUDE * np.asarray(slip_ratios))
            rows += new
            family += [name] * len(new)
            ratio += [r] * len(new)
    col = {k: np.array([row[k] for row in rows]) for k in rows[0]}
    dims = "case"
    data = {
        "zeta_total": variable(dims, col["zeta_total"], "1", "total damping ratio of the E-EBM point"),
        "zeta_friction": variable(dims, col["zeta_friction"], "1", "dNNM (friction) damping ratio"),
        "eebm_amplitude": variable(dims, col["eebm_amplitude"], "m", "E-EBM resonant amplitude"),
        "frf_amplitude": variable(dims, col["frf_amplitude"], "m", "forced-response peak amplitude"),
        "error": variable(dims, col["error"], "1", "E-EBM amplitude / forced-response peak - 1"),
        "frf_status": variable(dims, col["frf_status"], "1", "forced-response status (0 converged)"),
        "crossings": variable(dims, col["crossings"], "1", "backbone points at this forcing"),
        "family": variable(dims, np.array(family, dtype=object), "1", "damping family"),
        "stiffness_ratio": variable(dims, np.array(ratio), "1", "kt / k"),
    }
    return xr.Dataset(data, attrs={"H": H, "n_time_samples": NT, "slip_amplitude_m": SLIP_AMPLITUDE})


def limit(study: xr.Dataset, family: str, level: float = 0.05) -> float:
    """ζ_tot of ``family`` at which |error| first reaches ``level`` in increasing ζ_tot (log-linear
    interpolation between the bracketing cases; NaN if never reached)."""
    sel = study.family.values == family
    z, e = study.zeta_total.values[sel], np.abs(study.error.values[sel])
    order = np.argsort(z)
    z, e = z[order], e[order]
    above = np.flatnonzero(e >= level)
    if not above.size:
        return np.nan
    i = above[0]
    if i == 0:
        return float(z[0])
    w = (np.log(level) - np.log(e[i - 1])) / (np.log(e[i]) - np.log(e[i - 1]))
    return float(np.exp(np.log(z[i - 1]) + w * (np.log(z[i]) - np.log(z[i - 1]))))
