"""Contact state maps over the ring's upper surface (paper Figs. 6 and 11, middle and right columns)."""
from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np


def _surface_coords(ds):
    """Circumferential arc position (mm, from the sector centre) and axial position (mm)."""
    theta = np.arctan2(ds.y.values, ds.x.values)
    radius = np.hypot(ds.x.values, ds.y.values)
    return 1e3 * radius * theta, 1e3 * ds.z.values


def draw_surface_map(ax, static, values, vmax, cmap, title, label=None):
    """Per-pair ``values`` over the ring's upper surface of ``static`` on ``ax``, colour scale
    [0, vmax] with a colour bar (``label``)."""
    s, z = _surface_coords(static)
    sc = ax.scatter(s, z, c=values, vmin=0, vmax=vmax, cmap=cmap, s=40, marker="s")
    ax.set_title(title, fontsize=8)
    ax.set_ylabel("z (mm)", fontsize=8)
    ax.tick_params(labelsize=7)
    ax.figure.colorbar(sc, ax=ax, label=label)
    return sc


def draw_contact_maps(axes, datasets: dict) -> None:
    """Contact pressure (kPa) and gap (um) of each ring (label -> static dataset) on the rows of
    ``axes`` (rings × 2), one colour scale per quantity for all rings."""
    p_max = max(float(np.nanmax(ds.pressure.values)) for ds in datasets.values()) / 1e3
    g_max = max(float(np.nanmax(ds.gap.values)) for ds in datasets.values()) * 1e6
    for row, (label, ds) in zip(axes, datasets.items()):
        for ax, (values, vmax, name, cmap) in zip(row, [
                (ds.pressure.values / 1e3, p_max, "N0 / area (kPa)", "viridis"),
                (ds.gap.values * 1e6, max(g_max, 1e-3), "gap (um)", "magma")]):
            draw_surface_map(ax, ds, values, vmax, cmap,
                             f"{label}: {name}, {int(ds.attrs['n_in_contact'])} in contact")


def plot_contact_maps(datasets: dict, path) -> None:
    """One row per ring (label -> static dataset): contact pressure (kPa) and gap (um)."""
    rows = len(datasets)
    fig, axes = plt.subplots(rows, 2, figsize=(10, 1.7 * rows + 0.6), squeeze=False)
    draw_contact_maps(axes, datasets)
    for ax in axes[-1]:
        ax.set_xlabel("circumferential position (mm)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
