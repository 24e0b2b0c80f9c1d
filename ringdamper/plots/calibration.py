"""Backbones of the contact calibration and the contact-state study against the paper's default ring
(paper Fig. 8, §2.6)."""
from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from ..status import usable_status


def plot_backbones(curves: list[tuple[str, dict]], path, q_max: float = 1.0e-3) -> None:
    """Fig. 8-like figure: ω0, ζ, γ against |q_res,z| for labelled curves (first one bold), with
    the paper's §2.6 point (ζ_max 0.15 % at 0.164 mm, ω0 2.187) marked. A curve holds arrays over α:
    ``q`` (|q_res,z|, m), ``omega0``, ``zeta``, ``gamma`` (N) and ``status``; its usable points up
    to ``q_max`` (m) are drawn."""
    fig, axes = plt.subplots(1, 3, figsize=(11, 4.0), dpi=90)
    for k, (label, c) in enumerate(curves):
        ok = usable_status(c["status"]) & np.isfinite(c["q"]) & (c["q"] <= q_max)
        q = c["q"][ok] * 1e3
        style = dict(lw=2.2, color="k") if k == 0 else dict(lw=1.0)
        axes[0].plot(q, c["omega0"][ok], label=label, **style)
        axes[1].plot(q, 100 * c["zeta"][ok], **style)
        axes[2].plot(q, c["gamma"][ok], **style)
    axes[0].plot([0.164], [2.187], "r*", ms=10, label="paper §2.6")
    axes[1].plot([0.164], [0.15], "r*", ms=10)
    for ax, yl in zip(axes, (r"$\omega_0$ (normalised)", r"$\zeta$ (%)", r"$\gamma$ (N)")):
        ax.set_xlabel(r"$|q_{res,z}|$ (mm)")
        ax.set_ylabel(yl)
        ax.grid(alpha=0.3)
    axes[2].set_yscale("log")
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=4, fontsize=7, frameon=False)
    fig.tight_layout(rect=(0, 0.12, 1, 1))
    fig.savefig(path, dpi=90)
    plt.close(fig)
