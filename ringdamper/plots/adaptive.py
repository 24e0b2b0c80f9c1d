"""Figures of the adaptive design: the rings in kappa space coloured by the round that chose them
(validation rings marked), and the stopping trace (leave-one-out errors and predicted optimum per round)."""
from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from ..campaign.adaptive.design import round_of
from .labels import symbol

PAIRS = ((0, 1), (0, 2), (1, 2))


def plot_design(samples, path) -> None:
    """Three projections of the design: training rings coloured by round (0: initial design), validation
    rings as crosses."""
    kappa = samples[["kappa1", "kappa2", "kappa3"]].to_numpy()
    rounds = np.array([round_of(g) or 0 for g in samples.gid])
    train, val = (samples.split == "training").to_numpy(), (samples.split == "validation").to_numpy()
    last = int(rounds.max())
    cmap = plt.get_cmap("viridis", last + 1)
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.2), layout="constrained")
    for ax, (i, j) in zip(axes, PAIRS):
        dots = ax.scatter(kappa[train, i], kappa[train, j], c=rounds[train], cmap=cmap, s=22,
                          vmin=-0.5, vmax=last + 0.5, edgecolors="k", linewidths=0.3)
        ax.scatter(kappa[val, i], kappa[val, j], marker="x", c="tab:red", s=30, label="validation")
        ax.set(xlabel=f"$\\kappa_{i + 1}$", ylabel=f"$\\kappa_{j + 1}$", xlim=(-1.08, 1.08), ylim=(-1.08, 1.08),
               aspect="equal")
    fig.legend(handles=axes[0].get_legend_handles_labels()[0], loc="outside upper center", fontsize=8)
    fig.colorbar(dots, ax=axes, label="round that chose the ring (0: initial design)", shrink=0.8,
                 ticks=range(last + 1))
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_trace(trace, path) -> None:
    """Per round (x: training rings computed): each output's estimated validation error over its
    tolerance (the stop rule's accuracy test: <= 1), the predicted optimum's kappa and its zeta_max with
    the +-2 sigma band."""
    fig, axes = plt.subplots(1, 3, figsize=(13, 4))
    if trace.empty:
        fig.suptitle("fixed design (sampling.design: paper): no rounds", fontsize=10)
        fig.savefig(path, dpi=110)
        plt.close(fig)
        return
    n = trace.n_computed.to_numpy()
    for name in ("q_res_z", "omega0", "zeta", "gamma"):
        axes[0].plot(n, trace[f"ratio_{name}"], "o-", label=symbol(name))
    axes[0].axhline(1.0, color="k", ls=":", label="tolerance")
    axes[0].set(xlabel="training rings computed", ylabel="estimated validation RMSE / tolerance")
    axes[0].legend(fontsize=8)
    for i in (1, 2, 3):
        axes[1].plot(n, trace[f"optimum_kappa{i}"], "o-", label=f"$\\kappa_{i}$")
    axes[1].set(xlabel="training rings computed", ylabel="predicted optimum", ylim=(-1.08, 1.08))
    axes[1].legend(fontsize=8)
    z, s = 100 * trace.optimum_zeta_max.to_numpy(), 100 * trace.optimum_zeta_max_std.to_numpy()
    axes[2].plot(n, z, "o-", color="tab:blue")
    axes[2].fill_between(n, z - 2 * s, z + 2 * s, color="tab:blue", alpha=0.15, lw=0)
    axes[2].set(xlabel="training rings computed", ylabel=r"predicted $\zeta_{max}$ at the optimum (%)")
    axes[2].ticklabel_format(axis="y", useOffset=False)
    last = trace.iloc[-1]
    fig.suptitle(f"stop after round {int(last['round'])}: {last['reason'] or 'not stopped'}", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
