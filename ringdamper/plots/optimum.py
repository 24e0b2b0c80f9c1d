"""Optimum against default ring (paper Fig. 19): contact and dissipated-energy maps, backbones and
forced responses with their peaks against the E-EBM predictions."""
from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from ..status import usable_status
from .dnnm import draw_backbones, draw_energy_map
from .static import draw_contact_maps

STYLES = {"default": {"color": "k", "lw": 1.8}, "optimum": {"color": "tab:red", "lw": 1.8}}


def energy_at(dnnm, alpha: float) -> np.ndarray:
    """Energy dissipated per pair [J] at modal amplitude ``alpha``, linear in log α between the
    bracketing grid points."""
    s = np.log(dnnm.amplitude.values)
    e = dnnm.energy_dissipated.values
    return np.array([np.interp(np.log(alpha), s, e[:, j]) for j in range(e.shape[1])])


def draw_branch(ax, x, y, stable, **style) -> None:
    """Branch ``y(x)`` solid where ``stable`` (Hill's method), dashed where unstable; consecutive
    runs share their end point so the curve stays connected."""
    stable = np.asarray(stable, bool)
    cuts = np.flatnonzero(np.diff(stable.astype(int))) + 1
    for lo, hi in zip(np.r_[0, cuts], np.r_[cuts, stable.size]):
        ax.plot(x[lo:hi + 1], y[lo:hi + 1], "-" if stable[lo] else "--", **style)


def plot_optimum_maps(statics: dict, dnnms: dict, curves: dict, path) -> None:
    """Per ring (rows): N0 / area and gap at rest, and E_d at the E-EBM resonance of the highest
    forcing level (one colour scale per quantity)."""
    fig, axes = plt.subplots(len(statics), 3, figsize=(15, 1.9 * len(statics) + 0.7), squeeze=False)
    draw_contact_maps(axes[:, :2], statics)
    energies = {ring: energy_at(dnnms[ring], float(curves[ring][-1].eebm_alpha)) for ring in statics}
    vmax = 1e6 * max(np.nanmax(e) for e in energies.values())
    for ax, ring in zip(axes[:, 2], statics):
        top = curves[ring][-1]
        draw_energy_map(ax, statics[ring], energies[ring],
                        f"{ring}: E_d at the E-EBM resonance, gamma = {float(top.gamma):.3g} N, "
                        f"|q_res,z| = {1e3 * float(top.eebm_amplitude):.3f} mm", vmax=vmax)
    for ax in axes[-1]:
        ax.set_xlabel("circumferential position (mm)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_optimum_dynamics(dnnms: dict, curves: dict, path) -> None:
    """Top: both backbones (ω0, ζ, γ against |q_res,z|) with the forcing levels (dotted) and each
    ring's E-EBM resonances (circles). Bottom: forced responses at every level (solid), the
    backbones ω0(|q_res,z|) (dash-dotted), forced peaks (×) against E-EBM predictions (circles);
    unstable parts of the forced responses (Hill's method) dashed."""
    fig = plt.figure(figsize=(14, 8.5))
    grid = fig.add_gridspec(2, 3, height_ratios=[1, 1.25])
    top = [fig.add_subplot(grid[0, k]) for k in range(3)]
    draw_backbones(top, dnnms, STYLES)
    ax = fig.add_subplot(grid[1, :])
    for ring, ds in dnnms.items():
        color = STYLES[ring]["color"]
        ok = usable_status(ds.status.values)
        ax.plot(ds.omega0.values[ok], 1e3 * ds.q_res_z.values[ok], "-.", color=color, lw=0.9)
        for c in curves[ring]:
            q_e, w_e = 1e3 * float(c.eebm_amplitude), float(c.eebm_omega0)
            draw_branch(ax, c.omega0.values, 1e3 * c.amplitude.values, c.stable.values,
                        color=color, lw=1.1)
            ax.plot(float(c.peak_omega0), 1e3 * float(c.peak_amplitude), "x", color=color, ms=9, mew=2)
            ax.plot(w_e, q_e, "o", mfc="none", color=color, ms=9, mew=1.2)
            top[2].plot(q_e, float(c.gamma), "o", mfc="none", color=color, ms=6)
    for c in curves["default"]:
        top[2].axhline(float(c.gamma), color="0.5", ls=":", lw=0.8)
    ax.plot([], [], "k-", label="forced response (HBM), stable")
    ax.plot([], [], "k--", lw=1.1, label="forced response, unstable (Hill)")
    ax.plot([], [], "k-.", lw=0.9, label="backbone")
    ax.plot([], [], "kx", ms=9, mew=2, label="forced-response peak")
    ax.plot([], [], "ko", mfc="none", ms=9, label="E-EBM prediction")
    for ring in dnnms:
        ax.plot([], [], color=STYLES[ring]["color"], lw=6, alpha=0.6, label=ring)
    levels = ", ".join(f"{float(c.gamma):.3g}" for c in curves["default"])
    ax.set_title(f"forced responses at gamma = {levels} N", fontsize=9)
    ax.set_xlabel(r"$\omega_0$ (normalised excitation frequency)")
    ax.set_ylabel(r"$|q_{res,z}|$ (mm)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, ncol=2, loc="upper left")
    # frame: where some curve is above a tenth of its peak
    near = [c.omega0.values[c.amplitude.values > 0.1 * float(c.amplitude.max())]
            for cs in curves.values() for c in cs]
    lo, hi = min(w.min() for w in near), max(w.max() for w in near)
    ax.set_xlim(lo - 0.05 * (hi - lo), hi + 0.05 * (hi - lo))
    ax.set_ylim(0, 1.15e3 * max(float(c.amplitude.max()) for cs in curves.values() for c in cs))
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_surrogate_at_optimum(predicted: dict, computed, path) -> None:
    """ω0, ζ and γ against |q_res,z| at the optimum: computed backbone (black; open markers where
    the ring is held by the gauge) and the Kriging prediction (median) with its 95 % band (orange)."""
    from .surrogate import COMPUTED, PREDICTED, draw_band, fit_to_lines

    fig, axes = plt.subplots(1, 3, figsize=(13, 4))
    draw_backbones(axes, {"computed": computed}, {"computed": COMPUTED})
    for ax, name in zip(axes, ("omega0", "zeta", "gamma")):
        draw_band(ax, predicted["q_res_z"], predicted[name], predicted[f"{name}_lower"], predicted[f"{name}_upper"],
                  name, label="Kriging, 95 % band" if name == "omega0" else None, **PREDICTED)
        if name != "gamma":
            fit_to_lines(ax)
    axes[0].legend(fontsize=7)
    axes[1].set_title("kappa = (" + ", ".join(f"{k:.3f}" for k in computed.attrs["kappa"]) + ")",
                      fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
