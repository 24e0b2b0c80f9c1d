"""Contact state maps over the ring's upper surface (paper Figs. 6 and 11, middle and right columns)."""
from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np


def _surface_coords(ds):
    """Circumferential arc position (mm, from the sector centre) and axial position (mm)."""
    theta = np.arctan2(ds.y.values, ds.x.values)
    radius = np.hypot(ds.x.values, ds.y.values)
    return 1e3 * radius * theta, 1e3 * ds.z.values


def plot_contact_maps(datasets: dict, path) -> None:
    """One row per ring (label -> static dataset): contact pressure (kPa) and gap (um)."""
    rows = len(datasets)
    fig, axes = plt.subplots(rows, 2, figsize=(10, 1.7 * rows + 0.6), squeeze=False)
    p_max = max(float(np.nanmax(ds.pressure.values)) for ds in datasets.values()) / 1e3
    g_max = max(float(np.nanmax(ds.gap.values)) for ds in datasets.values()) * 1e6
    for row, (label, ds) in enumerate(datasets.items()):
        s, z = _surface_coords(ds)
        for col, (values, vmax, name, cmap) in enumerate([
                (ds.pressure.values / 1e3, p_max, "N0 / area (kPa)", "viridis"),
                (ds.gap.values * 1e6, max(g_max, 1e-3), "gap (um)", "magma")]):
            ax = axes[row, col]
            sc = ax.scatter(s, z, c=values, vmin=0, vmax=vmax, cmap=cmap, s=40, marker="s")
            ax.set_title(f"{label}: {name}, {int(ds.attrs['n_in_contact'])} in contact", fontsize=8)
            ax.set_ylabel("z (mm)", fontsize=8)
            ax.tick_params(labelsize=7)
            fig.colorbar(sc, ax=ax)
    for ax in axes[-1]:
        ax.set_xlabel("circumferential position (mm)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
