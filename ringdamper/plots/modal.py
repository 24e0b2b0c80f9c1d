"""ND diagram (Fig. 3), Campbell diagram (Fig. 5) and mode shapes (Fig. 4)."""
from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

FAMILY_STYLE = {"1B": "C0", "1T": "C1", "2B": "C2", "1D": "C3"}


def plot_nd_diagram(ds, path):
    fig, ax = plt.subplots(figsize=(6, 4.5))
    fam = ds.family.values
    for name, color in FAMILY_STYLE.items():
        nd, f = [], []
        for i, k in enumerate(ds.nd.values):
            hits = np.flatnonzero(fam[i] == name)
            if len(hits):
                nd.append(k)
                f.append(ds.omega0.values[i, hits[0]])
        ax.plot(nd, f, "o-", color=color, label=name)
    ax.set_xlabel("nodal diameter")
    ax.set_ylabel(r"normalised frequency $\omega_0$")
    ax.set_title(f"ND diagram at {ds.attrs['speed_rpm']:.0f} rpm (contact stuck)")
    ax.legend()
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def plot_campbell(ds, resonance, path, n_sectors: int):
    fig, ax = plt.subplots(figsize=(6, 4.5))
    rpm = ds.speed.values
    for j in ds.mode.values:
        ax.plot(rpm, ds.frequency.values[:, j], "r-", lw=1)
    nd, eo_target = ds.attrs["nd"], ds.attrs["engine_order"]
    fmax = ds.frequency.values.max() * 1.05
    for eo in range(1, 4 * n_sectors):
        if eo % n_sectors not in (nd, n_sectors - nd):
            continue
        line = eo * rpm / 60
        style = ("k-", 1.5) if eo == eo_target else ("0.7", 0.8)
        ax.plot(rpm, line, style[0], lw=style[1])
        if line[-1] < fmax:
            ax.text(rpm[-1], line[-1], f"EO {eo}", fontsize=7)
    ax.plot(resonance["speed_rpm"], resonance["frequency_hz"], "b*", ms=14,
            label=f"EO {eo_target} x {resonance['family']}-ND{nd}: {resonance['speed_rpm']:.0f} rpm")
    ax.set_ylim(0, fmax)
    ax.set_xlabel("speed (rpm)")
    ax.set_ylabel("frequency (Hz)")
    ax.set_title(f"Campbell diagram, ND {nd}")
    ax.legend(loc="upper left", fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def plot_mode_shapes(model, shapes, path):
    """Deformed sector (axial view and meridional view) of each mode, coloured by |u|."""
    fig, axes = plt.subplots(2, len(shapes), figsize=(3.2 * len(shapes), 6))
    x = model.nodes
    scale = 0.03 / max(np.abs(u).max() for _, _, u in shapes)
    for col, (f, fam, u) in enumerate(shapes):
        y = x + scale * u
        mag = np.linalg.norm(u, axis=1)
        for row, (i, j, lab) in enumerate([(0, 1, ("x", "y")), (0, 2, ("x", "z"))]):
            ax = axes[row, col]
            ax.scatter(y[:, i], y[:, j], c=mag, s=2, cmap="viridis")
            ax.set_aspect("equal")
            ax.set_xlabel(lab[0])
            ax.set_ylabel(lab[1])
        axes[0, col].set_title(f"{fam}: {f:.1f} Hz")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
