"""Forced Duffing oscillator by harmonic balance, the oracle of Hill's method (docs/method_limits.md §4).

``ẍ + 2ζẋ + x + κx³ = F cos ωt`` (hardening for κ > 0) in the real slots of
:class:`ringdamper.nonlinear.fourier.Fourier` (AFT for the cubic term), traced by pseudo-arc-length
continuation in ω (:func:`ringdamper.nonlinear.solvers.continuation.arclength`), every point classified by
:func:`ringdamper.nonlinear.harmonic_balance.stability.hill_exponents` (unit mass: Hill's Δ₂ = I). Its forced
response has two folds; the branch between them is unstable.
"""
from __future__ import annotations

import numpy as np
import xarray as xr

from ringdamper.io import variable
from ringdamper.nonlinear.fourier import Fourier
from ringdamper.nonlinear.harmonic_balance.stability import hill_exponents, is_stable
from ringdamper.nonlinear.solvers.continuation import CurveFunctions, StepControl, arclength
from ringdamper.nonlinear.solvers.jacobian import Evaluation

ZETA, KAPPA, FORCE = 0.01, 1.0, 0.01


def duffing(H: int, zeta: float = ZETA, kappa: float = KAPPA, force: float = FORCE):
    """``(fourier, fun, hill)``: ``fun(z, jacobian)`` the residual of ``z = [c, ω]`` in the
    continuation's convention, ``hill(ω)`` the first-order Hill matrix Δ₁."""
    fo = Fourier(H, 16 * H + 16)
    n = fo.C
    f = np.zeros(n)
    f[1] = force

    def blocks(omega):
        """Linear operator ``1 − (hω)² ± 2ζhω`` and Δ₁ = ``2ζ ± 2hω`` on every harmonic's slots."""
        L, D1 = np.zeros((n, n)), np.zeros((n, n))
        L[0, 0], D1[0, 0] = 1.0, 2 * zeta
        for h in range(1, H + 1):
            s, w = fo.slots(h), h * omega
            L[s, s] = [[1 - w * w, 2 * zeta * w], [-2 * zeta * w, 1 - w * w]]
            D1[s, s] = [[2 * zeta, 2 * w], [-2 * w, 2 * zeta]]
        return L, D1

    def fun(z, jacobian=True):
        c, omega = z[:-1], z[-1]
        L, _ = blocks(omega)
        x = fo.synth(c)
        r = L @ c + fo.analyse(kappa * x ** 3) - f
        if not jacobian:
            return Evaluation(r, None, None, n, None)
        Jc = L + fo.F @ (3 * kappa * x[:, None] ** 2 * fo.E)
        dL = np.zeros((n, n))                      # ∂L/∂ω
        for h in range(1, H + 1):
            s = fo.slots(h)
            dL[s, s] = [[-2 * h * h * omega, 2 * zeta * h], [-2 * zeta * h, -2 * h * h * omega]]
        return Evaluation(r, np.hstack([Jc, (dL @ c)[:, None]]), None, n, None)

    return fo, fun, lambda omega: blocks(omega)[1]


def duffing_frf(H: int, omega_start: float = 0.8, omega_end: float = 1.3):
    """Branch points ``z = [c, ω]`` (rows) and their Hill stability."""
    fo, fun, hill = duffing(H)
    z0 = np.zeros(fo.C + 1)
    z0[-1] = omega_start
    z0[1] = FORCE / (1 - omega_start ** 2)                 # linear response, polished by Newton
    for _ in range(30):
        ev = fun(z0)
        z0[:-1] -= np.linalg.solve(ev.J[:, :-1], ev.r)
    direction = np.zeros(fo.C + 1)
    direction[-1] = 1.0
    run = arclength(CurveFunctions(fun, stop=lambda z: z[-1] >= omega_end), z0, direction, np.ones(fo.C + 1),
                    StepControl(0.02, 1e-7, 0.05, tol=1e-11, max_iter=20, max_points=3000))
    if run.status != 0:
        raise RuntimeError(f"Duffing forced response: {run.reason}")
    z = np.array([p.z for p in run.points])
    stable = np.array([is_stable(hill_exponents(fun(zi).J[:, :-1], hill(zi[-1]), zi[-1]), zi[-1])
                       for zi in z])
    return z, stable


def stability_study(harmonics=(1, 3, 5)) -> xr.Dataset:
    """Duffing forced responses at every H with their Hill stability, stacked on a point axis."""
    omega, peak, stable, curve = [], [], [], []
    for H in harmonics:
        z, s = duffing_frf(H)
        fo = Fourier(H, 64 * H)
        omega.append(z[:, -1])
        peak.append(np.max(np.abs(fo.synth(z[:, :-1])), axis=1))
        stable.append(s)
        curve.append(np.full(len(s), H))
    cat = np.concatenate
    data = {"omega": variable("point", cat(omega), "1", "excitation frequency / linear frequency"),
            "amplitude": variable("point", cat(peak), "1",
                                  "peak displacement over the period (nondimensional)"),
            "stable": variable("point", cat(stable).astype(np.int8), "1",
                               "1 locally stable (Hill's method), 0 unstable"),
            "curve": variable("point", cat(curve), "1", "harmonics H of the curve")}
    coords = {"n_harmonics": variable("n_harmonics", list(harmonics), "1", "harmonics H")}
    return xr.Dataset(data, coords=coords, attrs={"zeta": ZETA, "kappa": KAPPA, "force": FORCE})
