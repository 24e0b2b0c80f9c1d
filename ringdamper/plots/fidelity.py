"""Charts of the fidelity study (docs/fidelity.md): cost against error per dial, the mesh levels,
and the campaign time against the surrogate's validation error."""
from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from matplotlib.ticker import NullFormatter, ScalarFormatter

from . import save_figure
from .modal import FAMILY_STYLE

RING_MARKERS = {"default": "o", "optimum": "s"}
FLOOR = 1e-7  # errors below this (the reference itself, or round-off) are drawn at it


def plot_dials(dials: pd.DataFrame, chosen: dict, tolerance: float, path) -> None:
    """One panel per dial: chain CPU per geometry (x, log) against the largest relative error of the
    user quantities (y, log), per ring; the reference value is left out (zero error, cost in the
    title), the current default is ringed, the chosen setting starred (no star: the reference is
    chosen); the tolerance is the dashed line."""
    names = list(dict.fromkeys(dials.dial))
    ncol = 3
    nrow = int(np.ceil(len(names) / ncol))
    fig, axes = plt.subplots(nrow, ncol, figsize=(4.2 * ncol, 3.4 * nrow), squeeze=False)
    for ax, dial in zip(axes.flat, names):
        d = dials[dials.dial == dial]
        for ring, g in d.groupby("ring"):
            g = g[~g.is_reference].sort_values("chain_cpu_s")
            err = np.clip(g.error_max.to_numpy(float), FLOOR, None)
            err = np.where(np.isfinite(err), err, 1.0)
            ax.plot(g.chain_cpu_s, err, marker=RING_MARKERS.get(ring, "^"), ls="-", label=ring)
            for x, y, v in zip(g.chain_cpu_s, err, g.value):
                ax.annotate(f"{v:g}", (x, y), textcoords="offset points", xytext=(4, 3), fontsize=7)
            de = g[g.is_default]
            ax.scatter(de.chain_cpu_s, np.clip(de.error_max, FLOOR, 1.0), s=160, facecolors="none",
                       edgecolors="k", zorder=5, label="current default" if ring == "default" else None)
            ch = g[g.value == chosen.get(dial)]
            ax.scatter(ch.chain_cpu_s, np.clip(ch.error_max, FLOOR, 1.0), marker="*", s=140, color="gold",
                       edgecolors="k", zorder=6, label="chosen" if ring == "default" else None)
        ax.axhline(tolerance, color="k", ls="--", lw=0.8)
        ax.set_xscale("log")
        ax.set_yscale("log")
        lo, hi = ax.get_xlim()
        if hi / lo < 4.0:                          # a narrow cost range: show it on a readable span
            mid = np.sqrt(lo * hi)
            ax.set_xlim(mid / 2.0, mid * 2.0)
        ax.xaxis.set_major_formatter(ScalarFormatter())
        ax.xaxis.set_minor_formatter(NullFormatter())
        ref = d[d.is_reference]
        cost = ", ".join(f"{c:.0f} s" for c in ref.chain_cpu_s)
        ax.set_title(f"{d.key.iloc[0]}: reference {ref.value.iloc[0]:g} ({cost})", fontsize=9)
        ax.set_xlabel("chain CPU per geometry (s)")
        ax.set_ylabel("max relative error")
        ax.grid(alpha=0.3, which="both")
    axes.flat[0].legend(fontsize=7)
    for ax in list(axes.flat)[len(names):]:
        ax.set_visible(False)
    save_figure(fig, path)


def plot_mesh(levels: pd.DataFrame, families, path) -> None:
    """Mesh levels: modal CPU (x, log) against |error| per family (y, log) relative to the quadratic
    Richardson limit; linear bricks dashed, quadratic solid, default (1x quadratic) ringed."""
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    for order, g in levels.groupby("order"):
        g = g.sort_values("factor")
        for fam in families:
            err = np.abs(g[f"error_{fam}"].to_numpy(float))
            ax.plot(g.cpu_time_s, np.clip(err, FLOOR, None), ls="-" if order == 2 else "--",
                    marker="o" if order == 2 else "x", color=FAMILY_STYLE.get(fam, "k"),
                    label=f"{fam}, {'27' if order == 2 else '8'}-node")
            if order == 2:
                for x, y, k in zip(g.cpu_time_s, err, g.factor):
                    ax.annotate(f"{k}x", (x, max(y, FLOOR)), textcoords="offset points", xytext=(3, 3), fontsize=7)
    de = levels[(levels.order == 2) & (levels.factor == 1)]
    for fam in families:
        ax.scatter(de.cpu_time_s, np.abs(de[f"error_{fam}"]), s=150, facecolors="none", edgecolors="k", zorder=5)
    ax.axhline(0.01, color="k", ls="--", lw=0.8)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("modal solve CPU, one ND (s)")
    ax.set_ylabel("|f / f(h->0) - 1| (27-node Richardson limit)")
    ax.set_title("mesh level and element order (ND 3, operating speed)")
    ax.legend(fontsize=7, ncol=2)
    ax.grid(alpha=0.3, which="both")
    save_figure(fig, path)


def plot_pareto(points: pd.DataFrame, path) -> None:
    """Campaign time (x, log) against the surrogate's validation error of zeta_max (y, log) per
    design and training-set size; the Pareto front drawn in black."""
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    for design, g in points.groupby("design"):
        g = g.sort_values("campaign_h")
        ax.plot(g.campaign_h, g.error, marker="o", label=design)
        for x, y, n in zip(g.campaign_h, g.error, g.n):
            ax.annotate(str(n), (x, y), textcoords="offset points", xytext=(3, 3), fontsize=7)
    front = points.sort_values("campaign_h")
    front = front[front.error <= front.error.cummin()]
    ax.step(front.campaign_h, front.error, where="post", color="k", lw=0.8, label="Pareto front")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("campaign time (h, estimated: chains / 2 cores + fits)")
    ax.set_ylabel(r"validation RMS relative error of $\zeta_{max}$")
    ax.set_title("training-set size and design (20 held-out geometries)")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3, which="both")
    save_figure(fig, path)
