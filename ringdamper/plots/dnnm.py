"""Backbones (paper Figs. 8, 12) and the dissipated-energy map (Fig. 9b)."""
from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from ..status import usable_status
from .static import draw_surface_map


def draw_backbones(axes, datasets: dict, styles: dict | None = None) -> None:
    """omega0, zeta (%) and gamma (N) against |q_res,z| (mm) on the three ``axes`` for each ring
    (label -> dnnm dataset; ``styles``: label -> line keywords, default: the default ring thick
    black); open markers: points where the ring's mean rigid-body equilibrium is held by the gauge
    (status 3, the ring would ratchet)."""
    for label, ds in datasets.items():
        status = ds.status.values
        ok = usable_status(status)
        gauged = (status == 3)[ok]
        q = 1e3 * ds.q_res_z.values[ok]
        style = (styles or {}).get(label, {"color": "k", "lw": 2} if label == "default" else {"lw": 1})
        values = (ds.omega0.values[ok], 100 * ds.zeta.values[ok], ds.gamma.values[ok])
        for k, (ax, v) in enumerate(zip(axes, values)):
            line, = ax.plot(q, v, label=label if k == 0 else None, **style)
            ax.plot(q[gauged], v[gauged], "o", mfc="none", ms=3, mew=0.6, color=line.get_color())
    for ax, name in zip(axes, [r"$\omega_0$", r"$\zeta$ (%)", r"$\gamma$ (N)"]):
        ax.set_xlabel(r"$|q_{res,z}|$ (mm)")
        ax.set_ylabel(name)
        ax.grid(alpha=0.3)
    axes[2].set_yscale("log")
    axes[0].legend(fontsize=7)


def plot_backbones(datasets: dict, path) -> None:
    """:func:`draw_backbones` of every ring (label -> dnnm dataset) in one row of three panels."""
    fig, axes = plt.subplots(1, 3, figsize=(13, 4))
    draw_backbones(axes, datasets)
    axes[1].set_title("open markers: ring held by the gauge (status 3, ratcheting)", fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def draw_energy_map(ax, static, energy, title, vmax=None):
    """Energy dissipated per cycle by each pair (J, shown in uJ) over the ring's upper surface."""
    e = 1e6 * np.asarray(energy)
    return draw_surface_map(ax, static, e, vmax if vmax is not None else np.nanmax(e), "inferno",
                            title, label=r"$E_d$ ($\mu$J per cycle)")


def plot_energy_map(dnnm, static, path, label: str = "default") -> None:
    """Energy dissipated per cycle by each pair at the amplitude of maximum damping."""
    ok = usable_status(dnnm.status.values)
    i = int(np.nanargmax(np.where(ok, dnnm.zeta.values, np.nan)))
    fig, ax = plt.subplots(figsize=(7, 2.6))
    draw_energy_map(ax, static, dnnm.energy_dissipated.values[i],
                    f"{label}: |q_res,z| = {1e3 * dnnm.q_res_z.values[i]:.3f} mm, "
                    f"zeta = {100 * dnnm.zeta.values[i]:.3f} % (maximum)")
    ax.set_xlabel("circumferential position (mm)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
