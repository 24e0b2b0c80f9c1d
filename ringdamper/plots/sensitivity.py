"""Sobol indices per response level (paper Figs. 18 and 20): circles first order, squares total
order, bars their confidence intervals; one colour per output."""
from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from .labels import COLOURS, symbol


def plot_sobol(ds, path, title: str) -> None:
    """One panel per |q_res,z| level of ``ds`` (dims output x parameter x level)."""
    levels = ds.level.values
    params = [str(p) for p in ds.parameter.values]
    outputs = [str(o) for o in ds.output.values]
    fig, axes = plt.subplots(1, len(levels), figsize=(3.6 * len(levels), 3.8), sharey=True, squeeze=False)
    x = np.arange(len(params))
    width = 0.8 / len(outputs)
    for ax, lev, tag in zip(axes[0], levels, "abcdefgh"):
        for k, name in enumerate(outputs):
            shift = x + (k - (len(outputs) - 1) / 2) * width
            for kind, marker, off in (("first_order", "o", -0.25), ("total_order", "s", 0.25)):
                v = ds[kind].sel(output=name, level=lev).values
                lo = ds[f"{kind}_lower"].sel(output=name, level=lev).values
                hi = ds[f"{kind}_upper"].sel(output=name, level=lev).values
                err = [np.clip(v - lo, 0, None), np.clip(hi - v, 0, None)]
                ax.errorbar(shift + off * width, v, yerr=err, fmt=marker, ms=5, capsize=2, color=COLOURS[name],
                            mfc="none" if kind == "total_order" else COLOURS[name],
                            label=f"{symbol(name)} {kind.replace('_', ' ')}" if tag == "a" else None)
        ax.set_xticks(x, [p.replace("kappa", "kappa ") for p in params])
        ax.set_title(f"({tag}) |q_res,z| = {1e3 * lev:g} mm", fontsize=9)
        ax.axhline(0, color="k", lw=0.5)
        ax.grid(alpha=0.3)
    axes[0, 0].set_ylabel("Sobol index")
    axes[0, 0].legend(fontsize=6)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
