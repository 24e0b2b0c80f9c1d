"""Figures of the Kriging surrogates: validation (paper Fig. 13), one-at-a-time sweeps (Figs. 14-16)
and the envelopes of the 50^3 grid (Fig. 17)."""
from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from .labels import label, scale

CURVES = ("omega0", "zeta", "gamma")
PREDICTED = {"color": "tab:orange", "ls": "--", "lw": 1.4}
COMPUTED = {"color": "k", "ls": "-", "lw": 1.4}


def draw_band(ax, q, y, lower, upper, name, **style):
    """Backbone y(q) (SI arrays) with its predictive band [lower, upper] of y, in display units."""
    x, s = 1e3 * np.asarray(q), scale(name)
    line, = ax.plot(x, s * y, **style)
    ax.fill_between(x, s * np.asarray(lower), s * np.asarray(upper), color=line.get_color(), alpha=0.15, lw=0)
    return line


def fit_to_lines(ax, margin=0.15):
    """y-limits from the axes' lines only, so that a wide predictive band does not squash them."""
    y = np.concatenate([np.asarray(line.get_ydata(), float) for line in ax.get_lines()])
    y = y[np.isfinite(y)]
    lo, hi = y.min(), y.max()
    pad = margin * (hi - lo) if hi > lo else max(abs(hi), 1.0) * 0.01
    ax.set_ylim(lo - pad, hi + pad)


def _finish(fig, axes, path, xlabel=None):
    for ax in np.ravel(axes):
        ax.grid(alpha=0.3)
        ax.ticklabel_format(axis="both", useOffset=False)
        ax.locator_params(axis="x", nbins=5)
        if xlabel:
            ax.set_xlabel(xlabel)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_predicted_vs_computed(val, path) -> None:
    """Fig. 13a-d: Kriging median against the computed value at every usable validation point
    (open markers: ring held by the gauge), with R2 and the coverage of the 95 % band."""
    names = [str(n) for n in val.output.values]
    fig, axes = plt.subplots(1, len(names), figsize=(4 * len(names), 4))
    usable = val.usable.values.astype(bool)
    held = val.held.values.astype(bool) & usable
    for ax, name, tag in zip(axes, names, "abcd"):
        s = scale(name)
        y, p = s * val[f"{name}_computed"].values, s * val[f"{name}_predicted"].values
        free = usable & ~held
        ax.plot(y[free], p[free], ".", ms=4, color="tab:blue", label="converged")
        ax.plot(y[held], p[held], "o", ms=4, mfc="none", mew=0.7, color="tab:red", label="held by the gauge")
        lims = [np.nanmin(y[usable]), np.nanmax(y[usable])]
        ax.plot(lims, lims, "k-", lw=0.8)
        m = val.sel(output=name)
        ax.set_title(f"({tag}) R2 = {float(m.r2):.4f}, within-alpha R2 = {float(m.r2_within):.3f}\n"
                     f"Q2 = {float(m.q2):.4f}, 95 % band coverage {100 * float(m.coverage):.0f} %", fontsize=8)
        ax.set_xlabel(f"computed {label(name)}")
        ax.set_ylabel(f"predicted {label(name)}")
    axes[0].legend(fontsize=7)
    _finish(fig, axes, path)


def plot_validation_cases(val, gids, path) -> None:
    """Fig. 13e-g: computed backbones (black; open markers where held by the gauge) against the
    predicted ones (orange dashed, median and 95 % band) of the validation geometries ``gids``."""
    fig, axes = plt.subplots(len(gids), 3, figsize=(13, 3.3 * len(gids)), squeeze=False)
    for row, gid in zip(axes, gids):
        g = val.sel(geometry=gid)
        ok = g.usable.values.astype(bool)
        held = g.held.values.astype(bool) & ok
        kappa = ", ".join(f"{float(g[f'kappa{i}']):.2f}" for i in (1, 2, 3))
        for ax, name in zip(row, CURVES):
            qc, yc = 1e3 * g.q_res_z_computed.values, scale(name) * g[f"{name}_computed"].values
            ax.plot(qc[ok], yc[ok], label="computed", **COMPUTED)
            ax.plot(qc[held], yc[held], "o", mfc="none", ms=4, color="k")
            draw_band(ax, g.q_res_z_predicted.values, g[f"{name}_predicted"].values, g[f"{name}_lower"].values,
                      g[f"{name}_upper"].values, name, label="Kriging, 95 % band", **PREDICTED)
            fit_to_lines(ax)
            ax.set_ylabel(label(name))
            ax.set_title(f"{gid}: kappa = ({kappa})", fontsize=9)
    axes[0, 0].legend(fontsize=7)
    _finish(fig, axes, path, xlabel=label("q_res_z"))


def plot_one_at_a_time(oat, i: int, path, n_curves: int = 9) -> None:
    """Figs. 14-16: backbones of [kappa_i, others 0] for ``n_curves`` values of kappa_i with 95 %
    bands (left; black dashed: default ring) and the output over (|q_res,z|, kappa_i) (right)."""
    sweep = oat.isel(parameter=i)
    values = sweep.value.values
    pick = np.unique(np.linspace(0, len(values) - 1, n_curves).round().astype(int))
    default = int(np.argmin(np.abs(values)))
    cmap = plt.get_cmap("viridis")
    fig, axes = plt.subplots(3, 2, figsize=(12, 10), layout="constrained")
    levels = 1e3 * oat.level.values
    for (side, top), name in zip(axes, CURVES):
        for j in pick:
            draw_band(side, sweep.q_res_z_mean.values[j], sweep[f"{name}_mean"].values[j],
                      sweep[f"{name}_lower"].values[j], sweep[f"{name}_upper"].values[j], name,
                      color=cmap((values[j] + 1) / 2), lw=1)
        side.plot(1e3 * sweep.q_res_z_mean.values[default], scale(name) * sweep[f"{name}_mean"].values[default],
                  "k--", lw=1.2, label="default [0, 0, 0]")
        fit_to_lines(side)
        side.set_ylabel(label(name))
        mesh = top.pcolormesh(levels, values, scale(name) * sweep[f"{name}_at_level"].values,
                              shading="auto", cmap="viridis")
        fig.colorbar(mesh, ax=top, label=label(name))
        top.set_ylabel(f"kappa{i + 1}")
    side_map = plt.cm.ScalarMappable(cmap=cmap, norm=plt.Normalize(-1, 1))
    fig.colorbar(side_map, ax=axes[:, 0], label=f"kappa{i + 1}", shrink=0.6, location="left")
    axes[0, 0].legend(fontsize=7)
    axes[0, 0].set_title(f"kappa{i + 1} in [-1, 1], others 0: backbones (median), 95 % bands", fontsize=9)
    axes[0, 1].set_title("top view: output at |q_res,z| (white: level not reached)", fontsize=9)
    for ax in np.ravel(axes):
        ax.grid(alpha=0.3)
        ax.set_xlabel(label("q_res_z"))
        ax.ticklabel_format(axis="y", useOffset=False)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_envelopes(grid, path) -> None:
    """Fig. 17: range of omega0, zeta, gamma over the explored grid against |q_res,z|, with the
    default ring (black dashed) and the optimum (red dashed), both predicted."""
    fig, axes = plt.subplots(1, 3, figsize=(14, 4))
    q = 1e3 * grid.level.values
    kappa = ", ".join(f"{k:.2f}" for k in grid.attrs["optimum_kappa"])
    for ax, name in zip(axes, CURVES):
        s = scale(name)
        ax.fill_between(q, s * grid[f"{name}_lower"].values, s * grid[f"{name}_upper"].values,
                        color="0.75", label=f"{grid.attrs['n_geometries']} geometries")
        ax.plot(q, s * grid[f"{name}_default"].values, "k--", label="default [0, 0, 0]")
        ax.plot(q, s * grid[f"{name}_optimum"].values, "r--", label=f"optimum [{kappa}]")
        ax.set_ylabel(label(name))
    axes[0].legend(fontsize=7)
    _finish(fig, axes, path, xlabel=label("q_res_z"))
