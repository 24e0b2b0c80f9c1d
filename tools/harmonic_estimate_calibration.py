"""Calibration of the harmonic-truncation error estimate
(:mod:`ringdamper.nonlinear.indicators.harmonic_estimate`) against solved truncations: the default ring
(κ = 0) and the separating-contact study's gap family.

For every usable point of the H = 3 backbone the estimate of raising it to H = 5 and to H = 7 (both step
rules) is set beside the actual change: the whole backbone continued at H = 5 and H = 7 (AFT samples
``⌈64 H / 3⌉``, the adaptive pass's), compared at equal α. A check solve
(:func:`ringdamper.nonlinear.harmonic_balance.epmc.resolve_point`, the adaptive pass's first start) is
timed at every slipping point for the cost. Writes the table as NetCDF (units, long_name) and the
predicted-against-actual chart (docs/investigations/2026-12-02-harmonic-error-estimate.md).

    python -m tools.harmonic_estimate_calibration WORKDIR OUT.nc OUT.png

``WORKDIR`` caches the default ring's static.nc, reduced.nc (harmonics 0..7) and backbones.
"""
from __future__ import annotations

import argparse
import pickle
import time
from pathlib import Path

import numpy as np
import xarray as xr

from ringdamper.config import load_config
from ringdamper.nonlinear.adaptive import SLIP_ZETA, time_samples
from ringdamper.nonlinear.harmonic_balance.epmc import epmc, resolve_point
from ringdamper.nonlinear.indicators.harmonic_estimate import (
    ESTIMATED,
    METHODS,
    estimate_raise,
    point_outputs,
    relative_changes,
)
from ringdamper.nonlinear.indicators.separation import separation_indicators
from ringdamper.status import usable_status
from ringdamper.studies.method_limits.harmonics import FAMILIES, ZETA_S, separating_oscillator

BASE_H, RAISED = 3, (5, 7)
GAP_ALPHA = np.geomspace(2e-3, 0.3, 40)     # the study's grid


def default_ring(workdir: Path) -> tuple[dict, object, float]:
    """The default ring's backbones at H = 3, 5, 7 (cached in ``workdir``), its contacts and ζ_s."""
    from ringdamper.nonlinear.stage import amplitude_grid, solve_backbone
    from ringdamper.reduction.stage import run_reduced
    from ringdamper.static.stage import run_static
    from ringdamper.studies.hub_calibration import crossing_speed

    cfg = load_config()
    cfg["reduction"]["n_harmonics"] = max(RAISED)
    if not (workdir / "reduced7.nc").exists():
        static, _, _ = run_static(cfg, (0.0, 0.0, 0.0))
        static.to_netcdf(workdir / "static.nc")
        run_reduced(cfg, (0.0, 0.0, 0.0)).to_netcdf(workdir / "reduced7.nc")
    static, reduced = xr.load_dataset(workdir / "static.nc"), xr.load_dataset(workdir / "reduced7.nc")
    out = {}
    for H in (BASE_H,) + RAISED:
        path = workdir / f"backbone_H{H}.pkl"
        if not path.exists():
            nt = time_samples(H, BASE_H, cfg["dnnm"]["n_time_samples"])
            bb, contacts, _, _ = solve_backbone(reduced, static, cfg, crossing_speed(cfg)[1],
                                                amplitude_grid(cfg["dnnm"]), H, nt, structure_harmonics=max(RAISED))
            with open(path, "wb") as f:
                pickle.dump({"backbone": bb, "contacts": contacts}, f)
        with open(path, "rb") as f:
            saved = pickle.load(f)
        out[H] = saved["backbone"]
    return out, saved["contacts"], cfg["dnnm"]["structural_damping_ratio"]


def gap_family() -> tuple[dict, object, float]:
    """The gap family's backbones at H = 3 (the study's 96 samples), 5 and 7 (32 samples a harmonic)."""
    p = FAMILIES["gap"]
    st, contacts = separating_oscillator(p["N0"], p["gap"], max(RAISED))
    return ({H: epmc(st, contacts, GAP_ALPHA, H=H, nt=32 * H, tol=1e-10) for H in (BASE_H,) + RAISED},
            contacts, ZETA_S)


def estimates(base, contacts, zeta_s: float, check: bool) -> dict:
    """Per usable point of the H = 3 backbone ``base``: the estimated relative changes (:data:`ESTIMATED`)
    to each H of :data:`RAISED` (the block step everywhere, the full Newton step at the slipping points),
    the estimate's seconds, and (``check``) the seconds and Newton iterations of a check solve at H = 5
    (the adaptive pass's first start) at the slipping points."""
    out = point_outputs(base, zeta_s)
    ok = usable_status(base.status)
    n = base.alpha.size
    _, lifting = separation_indicators(base, contacts, ok)
    table = {"lifting_pairs": lifting, "slipping": ok & (out["zeta"] > SLIP_ZETA)}
    for H in RAISED:
        models = {}
        for method in METHODS:
            est = {k: np.full(n, np.nan) for k in ESTIMATED + ("seconds",)}
            for i in np.flatnonzero(ok if method == "block" else table["slipping"]):
                e = estimate_raise(base, i, H, time_samples(H, BASE_H, base.nt), zeta_s, method, models,
                                   current={k: v[i] for k, v in out.items()})
                for k in ESTIMATED:
                    est[k][i] = e.change[k]
                est["seconds"][i] = e.seconds
            table.update({f"{method}_{k}_H{H}": v for k, v in est.items()})
    table["check_seconds_H5"], table["check_iterations_H5"] = np.full(n, np.nan), np.full(n, np.nan)
    for i in np.flatnonzero(table["slipping"]) if check else ():
        t = time.perf_counter()
        higher, _ = resolve_point(base, i, RAISED[0], time_samples(RAISED[0], BASE_H, base.nt), 1e-8, 8, models={})
        table["check_seconds_H5"][i] = time.perf_counter() - t
        table["check_iterations_H5"][i] = np.nan if higher is None else higher.iterations[0]
    return table


def actual_changes(backbones: dict, zeta_s: float) -> dict:
    """Per point, the relative change (:data:`ESTIMATED`) from the H = 3 backbone to each of :data:`RAISED`
    (NaN where one of them is not usable)."""
    outs = {H: point_outputs(b, zeta_s) for H, b in backbones.items()}
    ok = np.all([usable_status(b.status) for b in backbones.values()], axis=0)
    table = {}
    for H in RAISED:
        actual = {k: np.full(ok.size, np.nan) for k in ESTIMATED}
        for i in np.flatnonzero(ok):
            change = relative_changes({k: v[i] for k, v in outs[H].items()}, {k: v[i] for k, v in outs[BASE_H].items()})
            for k in ESTIMATED:
                actual[k][i] = change[k]
        table.update({f"actual_{k}_H{H}": v for k, v in actual.items()})
    return table


def cached_estimates(workdir: Path, base, contacts, zeta_s: float) -> dict:
    """:func:`estimates` of the default ring's H = 3 backbone, cached in ``workdir``."""
    path = workdir / "ring_estimates.pkl"
    if not path.exists():
        table = estimates(base, contacts, zeta_s, check=True)
        with open(path, "wb") as f:
            pickle.dump(table, f)
    with open(path, "rb") as f:
        return pickle.load(f)


def dataset(tables: dict, alphas: dict) -> xr.Dataset:
    """The tables of each system as one NetCDF dataset (variables ``<system>_<name>``, one α dimension each)."""
    ds = xr.Dataset()
    for system, table in tables.items():
        dim = f"{system}_alpha"
        ds[dim] = xr.DataArray(alphas[system], dims=dim, attrs={"units": "kg^0.5 m",
                                                                "long_name": f"{system}: modal amplitude"})
        for name, v in table.items():
            what = name.split("_H")[0].replace("_", " ")
            unit = "s" if "seconds" in name else "1"      # relative changes, counts, flags
            ds[f"{system}_{name}"] = xr.DataArray(np.asarray(v, float), dims=dim,
                                                  attrs={"units": unit, "long_name": f"{system}: {what}"
                                                         + (f", H = 3 to {name[-1]}" if "_H" in name else "")})
    ds.attrs["base_harmonics"] = BASE_H
    ds.attrs["made_by"] = "python -m tools.harmonic_estimate_calibration"
    return ds


def chart(ds: xr.Dataset, path: Path) -> None:
    """Estimated against actual largest relative change of ω, ζ, γ, |q_res,z| (block step), log-log."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6, 5.5))
    marks = {"ring": "o", "gap": "s"}
    colours = {5: "tab:blue", 7: "tab:red"}
    for system in marks:
        keys = ("omega", "zeta", "gamma", "q_res_peak") if system == "ring" else ("omega", "gamma", "q_res_peak")
        for H in RAISED:
            act = np.max([np.abs(ds[f"{system}_actual_{k}_H{H}"].values) for k in keys], axis=0)
            est = np.max([np.abs(ds[f"{system}_block_{k}_H{H}"].values) for k in keys], axis=0)
            ax.loglog(np.maximum(act, 1e-9), np.maximum(est, 1e-9), marks[system], mfc="none", color=colours[H],
                      label=f"{'default ring' if system == 'ring' else 'gap family (ζ left out)'}, H = 3 → {H}")
    ax.plot([1e-9, 1], [1e-9, 1], "k-", lw=0.8)
    for f in (3, 1 / 3):
        ax.plot([1e-9, 1], [1e-9 * f, f], "k:", lw=0.6)
    ax.axvline(0.01, color="grey", lw=0.6, ls="--")
    ax.axhline(0.01, color="grey", lw=0.6, ls="--")
    ax.set(xlabel="actual largest relative change (solved at H)", ylabel="estimated (one block step from H = 3)",
           xlim=(1e-9, 1), ylim=(1e-9, 1), title="Harmonic-truncation error estimate")
    ax.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("workdir", type=Path)
    ap.add_argument("out", type=Path)
    ap.add_argument("png", type=Path)
    args = ap.parse_args(argv)
    args.workdir.mkdir(parents=True, exist_ok=True)
    ring, contacts, zeta_s = default_ring(args.workdir)
    gap, gap_contacts, gap_zeta = gap_family()
    ring_estimates = cached_estimates(args.workdir, ring[BASE_H], contacts, zeta_s)
    tables = {"ring": {**ring_estimates, **actual_changes(ring, zeta_s)},
              "gap": {**estimates(gap[BASE_H], gap_contacts, gap_zeta, False), **actual_changes(gap, gap_zeta)}}
    ds = dataset(tables, {"ring": ring[BASE_H].alpha, "gap": GAP_ALPHA})
    ds.to_netcdf(args.out)
    chart(ds, args.png)


if __name__ == "__main__":
    main()
