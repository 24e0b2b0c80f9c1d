"""Contact state maps over the ring's upper surface (paper Figs. 6 and 11, middle and right columns)."""
from __future__ import annotations

import itertools

import matplotlib.pyplot as plt
import numpy as np

from ..static.closure import pair_closure, station_means
from ..static.surface import sector_position, surface_coords


def draw_surface_map(ax, static, values, vmax, cmap, title, label=None):
    """Per-pair ``values`` over the ring's upper surface of ``static`` on ``ax``, colour scale
    [0, vmax] with a colour bar (``label``)."""
    s, z = (1e3 * v for v in surface_coords(static))  # m -> mm
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


def _lines(ax, rows, x, y, key, label_of, scale=1.0, **style):
    """One line of ``y`` against ``x`` (x in um) per distinct ``key`` value of ``rows``, coloured by
    the value's rank."""
    for k, value in enumerate(sorted(dict.fromkeys(r[key] for r in rows), key=str)):
        sel = sorted((r for r in rows if r[key] == value), key=lambda r: r[x])
        ax.plot([1e6 * r[x] for r in sel], [scale * r[y] for r in sel], marker="o", ms=3,
                color=f"C{k}", label=label_of(value), **style)


def plot_variety_search(design_rows: list, ring_rows: list, configured: dict, path) -> None:
    """The contact-state search: rows of the paper's table reproduced against the radial clearance
    (the best kn / area of each clearance; one line per groove support, colour by arm length, line
    style by arm thickness, thick for the ``configured`` support), and the variety metric of each
    ring against the clearance at the ``configured`` kn and support (``configured``: the
    ``normal_stiffness_per_area``, ``arm_thickness`` and ``arm_length`` of the model)."""
    fig, axes = plt.subplots(2, 3, figsize=(13, 7.5))
    ax = axes[0, 0]
    thicknesses = sorted(dict.fromkeys(r["arm_thickness"] for r in design_rows))
    lengths = sorted(dict.fromkeys(r["arm_length"] for r in design_rows))
    support = ("arm_thickness", "arm_length")
    for (i, t), (j, length) in itertools.product(enumerate(thicknesses), enumerate(lengths)):
        rows = [r for r in design_rows if (r["arm_thickness"], r["arm_length"]) == (t, length)]
        clearances = sorted(dict.fromkeys(r["radial_clearance"] for r in rows))
        best = [max(r["rows_reproduced"] for r in rows if r["radial_clearance"] == c) for c in clearances]
        ax.plot(1e6 * np.array(clearances), np.array(best) + 0.04 * (i - 1), marker="o", ms=3,
                color=f"C{j}", ls=["-", "--", ":", "-."][i % 4],
                lw=2.5 if (t, length) == tuple(configured[k] for k in support) else 1.0,
                label=f"arm {1e3 * t:g} x {1e3 * length:g} mm")
    ax.set_ylabel("paper's rows reproduced (of 7), best kn")
    ax.set_ylim(-0.2, 7.2)
    ax.legend(fontsize=6, ncol=2)
    kn = configured["normal_stiffness_per_area"]
    at = [r for r in ring_rows if r["normal_stiffness_per_area"] == kn
          and all(r[k] == configured[k] for k in support)]
    arm = f"arm {1e3 * configured['arm_thickness']:g} x {1e3 * configured['arm_length']:g} mm"
    panels = [("open_fraction", 1.0, "fraction of pairs open"),
              ("concentration", 1.0, "peak / mean pressure"),
              ("n0_position", 1.0, "N0 centre of mass |theta| / theta_h"),
              ("max_gap", 1e6, "largest gap (um)"),
              ("gap_position", 1.0, "gap-weighted |theta| / theta_h")]
    for ax, (y, scale, label) in zip(axes.ravel()[1:], panels):
        _lines(ax, at, "radial_clearance", y, "ring", str, scale)
        ax.set_ylabel(label)
    axes[0, 2].set_yscale("log")
    axes[0, 1].legend(fontsize=7, title=f"kn {kn:.0e} N/m3, {arm}", title_fontsize=7)
    lo, hi = axes[0, 0].get_xlim()
    for ax in axes.ravel():
        ax.set_xlim(lo, hi)
        if lo < 0:
            ax.axvspan(lo, 0.0, color="0.92", zorder=0)
        ax.set_xlabel("radial clearance at rest (um; shaded: interference)")
        ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def plot_free_closure(states: dict, configured: str, half_angle: float, path) -> None:
    """Closure d_n = initial gap - gap (um) of all-open static states (label -> (static dataset,
    underside imprint)) against the angle from the sector centre: every pair of the ``configured``
    state, one line per axial position (left); each state's station means relative to the centre
    station (middle); the radial displacement of the support's underside on the sector boundary
    minus under the blade, against z (right). It is how the groove and the ring move apart under the
    centrifugal load, what a contact would absorb, and how little of it is sector-periodic."""
    fig, (ax, bx, cx) = plt.subplots(1, 3, figsize=(15, 4.2))
    static = states[configured][0]
    s = sector_position(static, half_angle)
    closure = 1e6 * pair_closure(static)
    z = np.round(1e3 * static.z.values, 3)
    for zv in np.unique(z):
        sel = np.flatnonzero(z == zv)
        order = sel[np.argsort(s[sel])]
        ax.plot(s[order], closure[order], marker="o", ms=3, label=f"z = {zv:g} mm")
    ax.set_ylabel("closure d_n without contact (um)")
    ax.set_title(f"{configured}: every pair (spread {np.ptp(closure):.2f} um)", fontsize=8)
    for label, (ds, imprint) in states.items():
        stations, mean = station_means(ds, sector_position(ds, half_angle))
        bx.plot(stations, 1e6 * (mean - mean[0]), marker="o", ms=3,
                label=f"{label} (spread {1e6 * np.ptp(mean):.3f} um)")
        cx.plot(1e3 * imprint.z.values, 1e6 * (imprint.boundary.values - imprint.centre.values),
                marker="o", ms=3, label=label)
    bx.set_ylabel("station mean closure - centre station (um)")
    bx.set_title("circumferential variation (what the default ring can feel)", fontsize=8)
    for a in (ax, bx):
        a.set_xlabel("|theta| / theta_h (0: under the blade, 1: sector boundary)")
    cx.axvspan(1e3 * static.z.values.min(), 1e3 * static.z.values.max(), color="0.85",
               label=f"ring band, {configured}")
    cx.set_xlabel("z (mm): rim, then the arm behind it")
    cx.set_ylabel("u_r(boundary) - u_r(under the blade) (um)")
    cx.set_title("support underside at the contact radius: sector-periodic part", fontsize=8)
    for a in (ax, bx, cx):
        a.legend(fontsize=7)
        a.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
