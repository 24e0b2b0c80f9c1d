"""The last-point study's figure (docs/investigations/last_point.md): the default
ring's backbone at the top of the amplitude grid, campaign trace against fine trace, with the
normal-force ratio n_min."""
from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import xarray as xr

from ..status import usable_status


def plot_separation(traces: dict[str, xr.Dataset], onset: float, path) -> None:
    """Frequency, ζ, γ and n_min against α for both traces of the study (``campaign``, ``fine``),
    the ``onset`` of separation (α where the first pair lifts off, NaN if none) marked."""
    fig, axes = plt.subplots(2, 2, figsize=(9, 6.5), dpi=90, sharex=True)
    styles = {"campaign": dict(marker="o", lw=1.2, color="tab:blue"),
              "fine": dict(marker=".", lw=1.0, color="tab:red")}
    lo = traces["fine"].amplitude.values[0] / 1.5
    for name, ds in traces.items():
        ok = usable_status(ds.status.values) & (ds.amplitude.values >= lo)
        a = ds.amplitude.values[ok]
        label = f"H = {ds.attrs['n_harmonics']}, {name} grid"
        axes[0, 0].plot(a, ds.frequency.values[ok], label=label, **styles[name])
        axes[0, 1].plot(a, 100 * ds.zeta.values[ok], **styles[name])
        axes[1, 0].plot(a, ds.gamma.values[ok], **styles[name])
        axes[1, 1].plot(a, ds.normal_force_ratio_min.values[ok], **styles[name])
    for ax, ylabel in zip(axes.ravel(), ("frequency (Hz)", r"$\zeta$ (%)", r"$\gamma$ (N)",
                                        r"min$_{p,t}$ $N/N_0$")):
        ax.set_ylabel(ylabel)
        ax.set_xscale("log")
        ax.grid(alpha=0.3, which="both")
        if np.isfinite(onset):
            ax.axvline(onset, color="k", ls=":", lw=1)
    axes[1, 1].axhline(0.0, color="k", lw=0.8)
    axes[1, 0].set_yscale("log")
    for ax in axes[1]:
        ax.set_xlabel(r"modal amplitude $\alpha$ (kg$^{1/2}$ m)")
    axes[0, 0].legend(fontsize=8)
    fig.suptitle("Default ring, top of the amplitude grid: dotted line = first pair lifts off"
                 + (f" (α = {onset:.3g})" if np.isfinite(onset) else ""), fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)
