"""E-EBM against forced responses, optimum against default (paper §3.4, Fig. 19g, Table 3).

*Backbone reading.* A dNNM backbone is known on the common grid of modal amplitudes α (log-spaced).
Its usable part is the leading run of converged points (status 0 or 3, finite values). Along it,
``log |q_res,z|``, ``log γ`` and ω are interpolated by monotone piecewise-cubic Hermite
interpolation (PCHIP, Fritsch & Carlson 1980) in ``s = log α``. PCHIP is monotone on every grid
interval where the data are, so a value bracketed by two neighbouring grid points has exactly one
root in between.

*Forcing levels.* The level for a target resonant amplitude ``q*`` of the default ring is
``γ* = γ(α*)`` at the first α along the backbone where ``|q_res,z|(α*) = q*``.

*E-EBM prediction at a forcing γ.* The resonant amplitude and frequency are the backbone's at the
first α where ``γ(α) = γ``. The E-EBM resonance is where the forced response touches the backbone
(energy balance, Eqs. 5-6). If ``γ(α)`` is not monotone (damping rising faster than the amplitude
where slip spreads), a level between a local maximum and the next local minimum is met 3 times:
the forced branch coming from low amplitude (the one the arc-length continuation follows from
below resonance) peaks at the first crossing; the other two lie on a detached branch (isola) or
beyond a jump. The first crossing is reported with the number of crossings (``eebm_crossings``),
so a non-monotone case is visible in the outputs and the table.

*Forced response.* HBM with arc-length continuation in excitation frequency
(:func:`ringdamper.nonlinear.harmonic_balance.frf.forced_response`), same reduced model, contact element,
H, Nt and structural damping as the dNNM, over ``band × ω_E-EBM``; the peak of the blade-tip Z time signal along the
branch (:func:`ringdamper.nonlinear.harmonic_balance.frf.resonance_peak`, the same measure as the
backbone's ``q_res_z``).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd
import xarray as xr
from scipy.interpolate import PchipInterpolator
from scipy.optimize import brentq

from ringdamper.io import variable
from ringdamper.nonlinear.harmonic_balance.frf import forced_response, resonance_peak
from ringdamper.nonlinear.normalisation import normalised_frequency
from ringdamper.status import usable_status


@dataclass
class EEBMBackbone:
    """Usable leading part of a backbone: ``alpha`` [kg^0.5 m], ``q`` (peak blade-tip Z) [m],
    ``gamma`` [N], ``omega`` [rad/s]; PCHIP interpolants in ``s = log α``."""

    alpha: np.ndarray
    q: np.ndarray
    gamma: np.ndarray
    omega: np.ndarray

    @classmethod
    def from_arrays(cls, alpha, q, gamma, omega, status) -> "EEBMBackbone":
        """Keep the leading run of points with a usable status and finite, positive values."""
        alpha, q, gamma, omega = (np.asarray(a, float) for a in (alpha, q, gamma, omega))
        good = (usable_status(status) & np.isfinite(q) & np.isfinite(gamma) & np.isfinite(omega)
                & (q > 0) & (gamma > 0))
        n = int(np.argmin(good)) if not good.all() else good.size
        if n < 2:
            raise ValueError(f"the backbone has {n} usable leading point(s); at least 2 are needed")
        return cls(alpha[:n], q[:n], gamma[:n], omega[:n])

    @classmethod
    def from_dnnm(cls, ds: xr.Dataset) -> "EEBMBackbone":
        """From a ``dnnm.nc`` dataset."""
        return cls.from_arrays(ds.amplitude.values, ds.q_res_z.values, ds.gamma.values,
                               2 * np.pi * ds.frequency.values, ds.status.values)

    @property
    def s(self) -> np.ndarray:
        return np.log(self.alpha)

    def crossings(self, name: str, value: float) -> list[float]:
        """Every ``s`` where the interpolated ``name`` (``"q"`` or ``"gamma"``) equals ``value``,
        in increasing α (one per bracketing grid interval)."""
        y = np.log(getattr(self, name)) - np.log(value)
        f = PchipInterpolator(self.s, y)
        roots = []
        for k in range(y.size - 1):
            if y[k] == 0.0:
                roots.append(self.s[k])
            elif y[k] * y[k + 1] < 0:
                roots.append(brentq(f, self.s[k], self.s[k + 1], xtol=1e-14))
        if y[-1] == 0.0:
            roots.append(self.s[-1])
        return roots

    def at(self, s: float) -> dict:
        """Interpolated ``alpha``, ``q``, ``gamma``, ``omega`` at ``s = log α``."""
        return {"alpha": float(np.exp(s)),
                "q": float(np.exp(PchipInterpolator(self.s, np.log(self.q))(s))),
                "gamma": float(np.exp(PchipInterpolator(self.s, np.log(self.gamma))(s))),
                "omega": float(PchipInterpolator(self.s, self.omega)(s))}

    def at_forcing(self, gamma: float) -> dict:
        """E-EBM resonance at forcing ``gamma``: the first crossing (see the module docstring),
        with ``crossings`` the number of crossings; NaNs and 0 if the level is out of range."""
        roots = self.crossings("gamma", gamma)
        if not roots:
            return {"alpha": np.nan, "q": np.nan, "gamma": gamma, "omega": np.nan, "crossings": 0}
        return {**self.at(roots[0]), "gamma": float(gamma), "crossings": len(roots)}


def forcing_levels(backbone: EEBMBackbone, targets, field: str = "frf.target_amplitudes") -> np.ndarray:
    """Forcing γ [N] at which the backbone's first resonant amplitude equals each target [m].

    Raises ``ValueError`` naming ``field`` and the reachable range if a target lies outside the
    usable backbone."""
    targets = np.asarray(targets, float)
    lo, hi = backbone.q.min(), backbone.q.max()
    bad = targets[(targets < lo) | (targets > hi)]
    if bad.size:
        raise ValueError(f"{field} = {targets.tolist()}: {bad.tolist()} m outside the amplitude range "
                         f"[{lo:.4g}, {hi:.4g}] m reached by the default ring's backbone")
    return np.array([backbone.at(backbone.crossings("q", t)[0])["gamma"] for t in targets])


def forced_curve(structure, contacts, backbone: EEBMBackbone, gamma: float, *, H: int, nt: int,
                 zeta_s: float, band=(0.985, 1.015), omega_reference: float) -> xr.Dataset:
    """Forced response at ``gamma`` [N] over ``band × ω_E-EBM`` with its peak and the E-EBM
    prediction, as the ``gamma_{i}.nc`` dataset; ``omega_reference`` is ω_stuck,default [rad/s] of
    the normalised frequency ω0. A level the usable backbone does not reach has no E-EBM
    prediction (NaN); its curve is centred on the backbone's last usable frequency."""
    pred = backbone.at_forcing(gamma)
    centre = pred["omega"] if np.isfinite(pred["omega"]) else backbone.omega[-1]
    frf = forced_response(structure, contacts, gamma, band[0] * centre, band[1] * centre,
                          H=H, nt=nt, zeta_s=zeta_s)
    if frf.points:
        peak = resonance_peak(frf)
        peak_q, peak_w, refined = peak.q_peak, peak.omega, peak.refined
    else:
        peak_q, peak_w, refined = np.nan, np.nan, False

    def w0(w):
        return normalised_frequency(w, omega_reference)

    point = {"point": variable("point", np.arange(len(frf.omega)), "1", "branch point index")}
    data = {
        "frequency": variable("point", frf.omega / (2 * np.pi), "Hz", "excitation frequency"),
        "omega0": variable("point", w0(frf.omega), "1", "normalised excitation frequency "
                           "2.195 omega / omega_stuck,default"),
        "amplitude": variable("point", frf.q_peak, "m",
                              "peak of the blade-tip Z displacement over the period"),
        "amplitude_h1": variable("point", frf.q_h1, "m",
                                 "first-harmonic magnitude of the blade-tip Z displacement"),
        "stable": variable("point", frf.stable.astype(np.int8), "1",
                           "1 where the point is locally stable (Hill's method), 0 unstable"),
        "growth_rate": variable("point", frf.growth, "1/s",
                                "largest real part of the point's Floquet exponents (Hill's method)"),
        "gamma": variable((), gamma, "N", "forcing level"),
        "peak_amplitude": variable((), peak_q, "m", "forced-response peak of |q_res,z|"),
        "peak_frequency": variable((), peak_w / (2 * np.pi), "Hz", "forced-response peak frequency"),
        "peak_omega0": variable((), w0(peak_w), "1", "forced-response peak normalised frequency"),
        "eebm_amplitude": variable((), pred["q"], "m", "E-EBM resonant |q_res,z| at this forcing"),
        "eebm_frequency": variable((), pred["omega"] / (2 * np.pi), "Hz", "E-EBM resonant frequency"),
        "eebm_omega0": variable((), w0(pred["omega"]), "1", "E-EBM resonant normalised frequency"),
        "eebm_alpha": variable((), pred["alpha"], "kg0.5 m", "modal amplitude of the E-EBM resonance"),
        "eebm_crossings": variable((), pred["crossings"], "1",
                                   "number of backbone points with this forcing (1: gamma monotone)"),
        "status": variable((), np.int8(frf.status), "1",
                           "0 reached the end of the band, 1 no convergence, 3 drift, 4 budget"),
    }
    attrs = {"reason": frf.reason, "n_harmonics": H, "n_time_samples": nt,
             "structural_damping_ratio": zeta_s, "band": np.asarray(band, float),
             "peak_refined": int(refined), "wall_time_s": frf.wall_time}
    return xr.Dataset(data, coords=point, attrs=attrs)


def table3(curves: dict) -> pd.DataFrame:
    """Table 3 from ``{ring: [gamma_i datasets in level order]}`` with rings ``default`` and
    ``optimum``: per level the forcing, per ring the E-EBM and forced-response resonant amplitudes
    [mm] and their relative difference (FRF / E-EBM − 1) [%], and the reduction
    ``1 − q_optimum / q_default`` [%] from each method."""
    rows = []
    if len(curves["default"]) != len(curves["optimum"]):
        raise ValueError("the default and optimum rings need one curve per forcing level each")
    for i, (d, o) in enumerate(zip(curves["default"], curves["optimum"])):
        if not np.isclose(float(d.gamma), float(o.gamma), rtol=1e-12):
            raise ValueError(f"level {i + 1}: default at {float(d.gamma)} N, optimum at {float(o.gamma)} N")
        row = {"level": i + 1, "gamma_N": float(d.gamma)}
        for ring, ds in (("default", d), ("optimum", o)):
            e, f = float(ds.eebm_amplitude), float(ds.peak_amplitude)
            row[f"{ring}_eebm_mm"] = 1e3 * e
            row[f"{ring}_frf_mm"] = 1e3 * f
            row[f"{ring}_frf_vs_eebm_pct"] = 100 * (f / e - 1)
            row[f"{ring}_frf_status"] = int(ds.status)
        for method in ("eebm", "frf"):
            ratio = row[f"optimum_{method}_mm"] / row[f"default_{method}_mm"]
            row[f"reduction_{method}_pct"] = 100 * (1 - ratio)
        rows.append(row)
    return pd.DataFrame(rows)
