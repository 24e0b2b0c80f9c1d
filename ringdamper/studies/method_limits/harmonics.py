"""Harmonic truncation when the contact separates (docs/method_limits.md §2).

System: a unit mass with a normal DoF ``x`` and a tangential DoF ``y`` coupled by the stiffness
matrix ``[[1, 0.3], [0.3, 1.5]]``, one 3-D friction pair (normal ``x``, tangent ``y``; ``kn = 2``,
``kt = 1``, μ = 0.3) and structural damping ζ_s = 1e-3, forced and observed on ``x``. Two families
make the contact separate over part of the period: a low preload ``N0`` (the pair opens when the
normal motion exceeds ``N0/kn``) and an initial gap (it closes only at large amplitude).

Along each backbone (dNNM + E-EBM), H = 1, 2, 3, 5 are compared with a converged reference
(``REFERENCE_H``): the frequency ω and damping ratio ζ at equal modal amplitude α, and the E-EBM
resonant amplitude at equal forcing γ (the quantity users read). The separation measure is the
fraction of the period during which the pair is open in the reference solution; the truncation
indicator ε_H is :func:`ringdamper.nonlinear.indicators.truncation.highest_harmonic_fraction`. Amplitudes at
equal forcing are read as the campaign reads them (first backbone point at that forcing) on both
backbones; ζ errors are relative to the largest reference ζ of the family (where the pair sticks
or stays open ζ vanishes and a pointwise relative error would only measure round-off).
"""
from __future__ import annotations

import numpy as np
import xarray as xr

from ringdamper.campaign.forced_check import EEBMBackbone
from ringdamper.io import variable
from ringdamper.nonlinear.contact.friction import FrictionContacts
from ringdamper.nonlinear.harmonic_balance.eebm import eebm
from ringdamper.nonlinear.harmonic_balance.epmc import epmc
from ringdamper.nonlinear.harmonic_balance.structure import Structure
from ringdamper.nonlinear.indicators.truncation import highest_harmonic_fraction

REFERENCE_H = 11
HARMONICS = (1, 2, 3, 5)
ZETA_S = 1e-3
FAMILIES = {"preload": {"N0": 0.05, "gap": 0.0}, "gap": {"N0": 0.0, "gap": 0.02}}


def separating_oscillator(N0: float, gap: float, H: int):
    """The two-DoF system of the module doc."""
    K = np.array([[1.0, 0.3], [0.3, 1.5]])
    B = np.array([[1.0, 0.0], [0.0, 1.0], [0.0, 0.0]])
    e = np.array([1.0, 0.0])
    st = Structure.real(np.eye(2), K, B, e, e, H=H)
    return st, FrictionContacts(kn=2.0, kt=1.0, mu=0.3, N0=N0, gap=gap)


def backbone(N0: float, gap: float, H: int, alpha: np.ndarray):
    """dNNM + E-EBM at ``H``, its open fraction per α and ε_H."""
    st, c = separating_oscillator(N0, gap, H)
    nt = max(64, 32 * H)
    bb = epmc(st, c, alpha, H=H, nt=nt, tol=1e-10)
    res = eebm(bb, ZETA_S)
    is_open = np.full(alpha.size, np.nan)
    for i in range(alpha.size):
        if np.isfinite(bb.omega[i]):
            dn = bb.model.fourier.synth(bb.d[i][:, 0])               # normal gap signal
            is_open[i] = np.mean(c.N0[0] + c.kn[0] * (dn - c.gap[0]) <= 0)
    eps = highest_harmonic_fraction(bb.model.modal, bb.eta, bb.omega)
    return res, is_open, eps


def _curve(res) -> EEBMBackbone:
    return EEBMBackbone.from_arrays(res.alpha, res.q_res_peak, res.gamma, res.omega, res.status)


def truncation_study(alpha=np.geomspace(2e-3, 0.3, 40), families=FAMILIES, harmonics=HARMONICS,
                     reference_H: int = REFERENCE_H) -> xr.Dataset:
    """Relative errors of ω, ζ (at equal α) and of the E-EBM amplitude (at equal γ) of every H
    against ``reference_H``, with the reference's open fraction and ε_H, per family and α."""
    shape = (len(families), len(harmonics), alpha.size)
    err = {k: np.full(shape, np.nan) for k in ("omega", "zeta", "amplitude")}
    eps = np.full(shape, np.nan)
    opened = np.full((len(families), alpha.size), np.nan)
    for f, params in enumerate(families.values()):
        ref, opened[f], _ = backbone(params["N0"], params["gap"], reference_H, alpha)
        ok = ref.status == 0
        zeta_scale = np.nanmax(ref.zeta[ok])
        ref_curve = _curve(ref)
        for j, H in enumerate(harmonics):
            res, _, eps[f, j] = backbone(params["N0"], params["gap"], H, alpha)
            good = ok & (res.status == 0)
            err["omega"][f, j, good] = res.omega[good] / ref.omega[good] - 1
            err["zeta"][f, j, good] = (res.zeta[good] - ref.zeta[good]) / zeta_scale
            curve = _curve(res)
            for i in np.flatnonzero(ok):
                err["amplitude"][f, j, i] = (curve.at_forcing(ref.gamma[i])["q"]
                                             / ref_curve.at_forcing(ref.gamma[i])["q"] - 1)
    dims = ("family", "n_harmonics", "amplitude")
    coords = {"family": variable("family", np.array(list(families), dtype=object), "1",
                                 "separating-contact family (low preload or initial gap)"),
              "n_harmonics": variable("n_harmonics", list(harmonics), "1", "harmonics H"),
              "amplitude": variable("amplitude", alpha, "kg0.5 m", "modal amplitude alpha")}
    data = {f"{k}_error": variable(dims, v, "1", f"relative error of {label} against H = {reference_H}")
            for (k, v), label in zip(err.items(), ("omega at equal alpha",
                                                   "zeta at equal alpha (to its largest value)",
                                                   "the E-EBM amplitude at equal forcing"))}
    data["highest_harmonic_energy"] = variable(dims, eps, "1",
                                               "fraction of the vibration energy in harmonic H")
    data["open_fraction"] = variable(("family", "amplitude"), opened, "1",
                                     f"fraction of the period the pair is open (H = {reference_H})")
    return xr.Dataset(data, coords=coords, attrs={"reference_H": reference_H, "zeta_s": ZETA_S})


def worst_error(study: xr.Dataset, quantities=("omega", "amplitude")) -> xr.DataArray:
    """Largest |relative error| of ``quantities`` (of ω, ζ, amplitude) per family, H and α."""
    return np.abs(xr.concat([study[f"{k}_error"] for k in quantities],
                            "quantity")).max("quantity", skipna=True)


def indicator_limit(study: xr.Dataset, level: float = 0.01) -> float:
    """Smallest ε_H among the points whose ω or amplitude error exceeds ``level`` (NaN if none):
    below it every such error of the study is within ``level`` of the reference."""
    worst, eps = worst_error(study).values, study.highest_harmonic_energy.values
    bad = (worst > level) & np.isfinite(eps)
    return float(np.min(eps[bad])) if np.any(bad) else np.nan
