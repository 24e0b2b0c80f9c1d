"""Charts of the method-limit studies (docs/method_limits.md): each draws the dataset of its study
(:mod:`ringdamper.studies.method_limits`)."""
from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr

from ..nonlinear.harmonic_balance.eebm import ZETA_LIMIT
from ..nonlinear.indicators.truncation import THRESHOLD
from .optimum import draw_branch

MARKERS = {"structural": "s", "friction_1dof": "o", "friction_2dof": "^", "preload": "o", "gap": "^"}


def plot_eebm_validity(study: xr.Dataset, path) -> None:
    """|E-EBM amplitude error| against ζ_tot (log–log) per family, the exact linear curve, the 5 %
    line and the validity limit."""
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for fam in dict.fromkeys(study.family.values):
        sel = study.family.values == fam
        ax.loglog(study.zeta_total.values[sel], np.abs(study.error.values[sel]),
                  MARKERS.get(fam, "o"), mfc="none", label=fam.replace("_", " "))
    z = np.geomspace(3e-3, 0.7, 200)
    ax.loglog(z, 1 - np.sqrt(1 - z ** 2), "k-", lw=0.8, label=r"linear: $1-\sqrt{1-\zeta^2}$")
    ax.axhline(0.05, color="tab:red", ls="--", lw=1, label="5 %")
    ax.axvline(ZETA_LIMIT, color="0.4", ls=":", lw=1, label=rf"validity limit $\zeta_{{tot}}$ = {ZETA_LIMIT:g}")
    ax.set_xlabel(r"total damping ratio $\zeta_{tot}$ of the E-EBM point")
    ax.set_ylabel("|E-EBM amplitude / forced peak − 1|")
    ax.set_ylim(1e-7, 1)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7, loc="upper left")
    ax.set_title("E-EBM against the forced response (H = 1)", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_harmonics(study: xr.Dataset, worst: xr.DataArray, path) -> None:
    """Errors of each H against the converged reference: ω and amplitude (``worst``, the larger of
    the two per family, H and α) and ζ against the open fraction of the period, and ω/amplitude
    against the highest-harmonic energy fraction ε_H with the warning threshold."""
    zeta = np.abs(study.zeta_error)
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.3))
    colours = dict(zip(study.n_harmonics.values, ("tab:red", "tab:orange", "tab:blue", "tab:green")))
    for fam in study.family.values:
        opened = study.open_fraction.sel(family=fam).values
        for H in study.n_harmonics.values:
            e = worst.sel(family=fam, n_harmonics=H).values
            eps = study.highest_harmonic_energy.sel(family=fam, n_harmonics=H).values
            kw = dict(color=colours[H], mfc="none", ls="none", marker=MARKERS[fam], ms=5)
            axes[0].semilogy(opened, np.maximum(e, 1e-7), **kw)
            axes[1].semilogy(opened, np.maximum(zeta.sel(family=fam, n_harmonics=H).values, 1e-7), **kw)
            if H > 1:
                axes[2].loglog(eps, np.maximum(e, 1e-7), **kw)
    for H, c in colours.items():
        axes[0].plot([], [], "s", color=c, label=f"H = {H}")
    for fam in study.family.values:
        axes[0].plot([], [], MARKERS[fam], color="k", mfc="none", label=f"{fam} family")
    ref = study.attrs["reference_H"]
    labels = (f"|relative error| vs H = {ref}: worst of ω, amplitude at equal γ",
              f"|ζ error| vs H = {ref} / largest ζ of the family",
              f"|relative error| vs H = {ref}: worst of ω, amplitude at equal γ")
    for ax, lab in zip(axes, labels):
        ax.axhline(0.01, color="tab:red", ls="--", lw=1)
        ax.set_ylabel(lab, fontsize=8)
        ax.grid(alpha=0.3, which="both")
        ax.set_ylim(1e-7, 10)
    for ax in axes[:2]:
        ax.set_xlabel("fraction of the period with the contact open (reference)")
    axes[2].set_xlabel(r"energy fraction in the highest harmonic $\varepsilon_H$ (H ≥ 2)")
    axes[2].axvline(THRESHOLD, color="0.4", ls=":", lw=1, label=f"warning threshold {THRESHOLD:g}")
    axes[2].set_xlim(1e-8, 0.1)
    axes[0].legend(fontsize=7, ncol=2)
    axes[2].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_kriging_coverage(study: xr.Dataset, path) -> None:
    """±2σ coverage against the training size: ML and calibrated variance, on the validation split,
    near the boundary and inside, with the nominal rate."""
    fig, ax = plt.subplots(figsize=(8.6, 4.4))
    n = study.n_training.values
    styles = {"validation": "-", "near_boundary": "--", "interior": ":"}
    colours = {"ml": "tab:red", "jackknife": "tab:blue"}
    for cal in study.calibration.values:
        for group, ls in styles.items():
            ax.plot(n, 100 * study.coverage.sel(calibration=cal, group=group).values, ls,
                    marker="o", color=colours[str(cal)], label=f"{cal}, {group.replace('_', ' ')}")
    ax.axhline(100 * study.attrs["nominal"], color="k", lw=0.8, label=f"nominal {100 * study.attrs['nominal']:.1f} %")
    ax.set_xlabel("training geometries")
    ax.set_ylabel("points within ±2σ (%)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.02, 1.0))
    ax.set_title(f"Kriging ±2σ coverage on held-out geometries (boundary margin "
                 f"{study.attrs['boundary_margin']:g})", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_stability(study: xr.Dataset, path) -> None:
    """Duffing forced responses at every H: stable solid, unstable (Hill) dashed."""
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for H, c in zip(study.n_harmonics.values, ("tab:red", "tab:blue", "tab:green")):
        sel = study.curve.values == H
        draw_branch(ax, study.omega.values[sel], study.amplitude.values[sel],
                    study.stable.values[sel].astype(bool), color=c, lw=1.2)
        ax.plot([], [], color=c, label=f"H = {H}")
    ax.plot([], [], "k--", label="unstable (Hill)")
    ax.set_xlabel(r"excitation frequency $\omega$ (linear frequency 1)")
    ax.set_ylabel("peak displacement over the period")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(r"Duffing $\ddot x + 0.02\dot x + x + x^3 = 0.01\cos\omega t$ (the H curves overlap)",
                 fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
