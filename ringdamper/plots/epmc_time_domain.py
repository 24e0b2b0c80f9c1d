"""The time-domain check of the EPMC (docs/investigations/epmc_time_domain.md):
harmonic-balance backbones at several H against time-domain shooting."""
from __future__ import annotations

import matplotlib.pyplot as plt
import matplotlib.ticker


def plot_comparison(tables: dict, path: str) -> None:
    """ω/ω_stuck and ζ against α/α_first slip for every chain of ``tables`` (seed → table of
    :func:`ringdamper.studies.epmc_time_domain.compare`): HBM lines per H, shooting markers, the
    free-system mode the branch approaches dashed."""
    fig, axes = plt.subplots(2, len(tables), figsize=(4.2 * len(tables), 6.4), squeeze=False,
                             sharex="col")
    for col, (seed, t) in enumerate(tables.items()):
        w0 = t.omega_stuck.iloc[0]
        x = t.alpha / t.alpha_slip
        ax_w, ax_z = axes[0, col], axes[1, col]
        for H, g in t.groupby("H"):
            ok = g.status == 0
            ax_w.plot(x[g.index][ok], g.omega[ok] / w0, ".-", ms=3, lw=1, label=f"HBM H = {H}")
            ax_z.plot(x[g.index][ok], g.zeta[ok], ".-", ms=3, lw=1)
        s = t.dropna(subset=["omega_shoot_4096"])
        ax_w.plot(x[s.index], s.omega_shoot_4096 / w0, "ko", mfc="none", ms=8, label="time domain")
        ax_z.plot(x[s.index], s.zeta_shoot_4096, "ko", mfc="none", ms=8)
        free = s.omega_free.iloc[-1] / w0
        ax_w.axhline(free, color="grey", ls="--", lw=1)
        ax_w.text(x.min(), free, f" free-system mode {int(s.free_mode.iloc[-1]) + 1}",
                  va="top", fontsize=7, color="grey")
        ax_w.axhline(1.0, color="grey", ls=":", lw=1)
        ax_w.text(x.max(), 1.0, "stuck mode 1 ", va="bottom", ha="right", fontsize=7,
                  color="grey")
        ax_w.set_title(f"jenkins_chain({seed})")
        ax_w.set_ylabel("ω / ω_stuck")
        ax_z.set_ylabel("ζ")
        ax_z.set_xlabel("α / α_first slip")
        for ax in (ax_w, ax_z):
            ax.set_xscale("log")
            ax.set_xticks([0.8, 1, 2, 3, 4])
            ax.xaxis.set_major_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
            ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
            ax.grid(alpha=0.3)
    axes[0, 0].legend(fontsize=7, loc="center right")
    fig.suptitle("EPMC backbones: harmonic balance vs time-domain shooting", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)
