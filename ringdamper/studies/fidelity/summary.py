"""Tables of the fidelity study: per case its cost and errors, the chosen setting of each dial (the
cheapest whose error is below the tolerance on every quantity and ring) and the campaign time.

Cost is the chain's CPU time per geometry (static + reduction + dNNM, s; the wall time on an idle
core) and its peak resident memory (MB). The campaign time at a fidelity is estimated as
``n_geometries x chain CPU / n_cores`` (the geometries' chains dominate; docs/fidelity.md).
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from ...status import usable_status
from .dials import DEFAULT, case_key, default_value, dial_rings, dials, rings, value_label
from .quantities import gamma_at, relative_errors, user_quantities

COST_KEYS = ("static_cpu_s", "reduction_cpu_s", "dnnm_cpu_s", "chain_cpu_s", "chain_time_s", "peak_rss_mb")


def case_rows(config: dict, cases: dict) -> list[dict]:
    """One row per (ring, dial, value): cost, user quantities and their relative errors against the
    dial's finest value (``error_<quantity>``, ``error_max`` the largest). ``cases`` maps the case
    keys of :func:`dials.dial_cases` to their dnnm datasets."""
    fid = config["fidelity"]
    levels = config["sensitivity"]["levels"]
    max_level = config["exploration"]["optimum_max_level"]
    gammas = gamma_at(cases[(next(iter(rings(fid))), DEFAULT, DEFAULT)], config["frf"]["target_amplitudes"])
    rows = []
    for dial, spec in dials(fid).items():
        for ring in dial_rings(fid, dial):
            labels = [value_label(v) for v in spec["values"]]
            q = {lb: user_quantities(cases[case_key(config, ring, dial, lb)], levels, gammas, max_level)
                 for lb in labels}
            ref = q[labels[-1]]
            for v, lb in zip(spec["values"], labels):
                rows.append({"ring": ring, "dial": dial, "key": spec["key"], "value": v,
                             "is_default": lb == value_label(default_value(config, dial)),
                             "is_reference": lb == labels[-1],
                             **case_summary(cases[case_key(config, ring, dial, lb)], q[lb], ref)})
    return rows


def case_summary(ds: xr.Dataset, quantities: dict, reference: dict) -> dict:
    """Cost (:data:`COST_KEYS`), failed points, user ``quantities`` of the case ``ds`` and their
    relative errors against ``reference`` (``error_<quantity>``, ``error_max`` the largest)."""
    err = relative_errors(quantities, reference)
    return {**{k: float(ds.attrs[k]) for k in COST_KEYS},
            "n_failed": int(np.sum(~usable_status(ds.status.values))),
            **quantities, **{f"error_{k}": e for k, e in err.items()}, "error_max": max(err.values())}


def choose(rows: list[dict], tolerance: float, current: dict, noise: float = 0.1) -> dict:
    """Per dial: among the values whose ``error_max`` is below ``tolerance`` on every ring, those whose
    chain CPU (largest over rings) is within ``noise`` of the cheapest, and of these the most accurate
    (the reference value when none is below the tolerance). The ``current`` value is kept when it is
    below the tolerance too and the choice saves less than ``noise`` of its CPU: differences within
    the timing noise of a shared machine do not justify changing results."""
    out = {}
    for dial in dict.fromkeys(r["dial"] for r in rows):
        by_value: dict = {}
        for r in (r for r in rows if r["dial"] == dial):
            b = by_value.setdefault(r["value"], {"cpu": 0.0, "error": 0.0})
            b["cpu"] = max(b["cpu"], r["chain_cpu_s"])
            b["error"] = max(b["error"], 0.0 if r["is_reference"] else r["error_max"])
        ok = [v for v, b in by_value.items() if b["error"] < tolerance]
        if not ok:
            out[dial] = list(by_value)[-1]
            continue
        cheapest = min(by_value[v]["cpu"] for v in ok)
        best = min((v for v in ok if by_value[v]["cpu"] <= (1.0 + noise) * cheapest),
                   key=lambda v: by_value[v]["error"])
        keep = current.get(dial)
        if keep in ok and by_value[best]["cpu"] > (1.0 - noise) * by_value[keep]["cpu"]:
            best = keep
        out[dial] = best
    return out


def chain_cpu(rows: list[dict], settings: dict) -> dict:
    """Per-geometry CPU (s) per stage at ``settings`` (dial -> value): the default case's stage times
    scaled by each dial's ratio (its value's CPU over the default's, mean over rings) on the stages
    it touches; the reduction also grows with the harmonics of the dNNM."""
    default = [r for r in rows if r["is_default"]]
    stages = {s: float(np.mean([r[f"{s}_cpu_s"] for r in default])) for s in ("static", "reduction", "dnnm")}
    for dial, value in settings.items():
        for s in ("reduction", "dnnm"):
            num = [r[f"{s}_cpu_s"] for r in rows if r["dial"] == dial and r["value"] == value]
            den = [r[f"{s}_cpu_s"] for r in rows if r["dial"] == dial and r["is_default"]]
            if num and den:
                stages[s] *= float(np.mean(num) / np.mean(den))
    stages["chain"] = sum(stages.values())
    return stages


def campaign_hours(chain_cpu_s: float, n_geometries: int, n_cores: int) -> float:
    """Estimated campaign wall time (h): the chains of ``n_geometries`` spread over ``n_cores``."""
    return chain_cpu_s * n_geometries / n_cores / 3600.0


def read_cases(paths: dict) -> dict:
    """Case key -> dataset (loaded)."""
    return {key: xr.load_dataset(p) for key, p in paths.items()}


def campaign_summary(config: dict, rows: list[dict], n_geometries: int, n_cores: int) -> dict:
    """Chosen settings and the chain CPU and campaign time at the current defaults, the chosen
    settings and the converged reference (finest value of every dial)."""
    fid = config["fidelity"]
    current = {d: default_value(config, d) for d in dials(fid)}
    chosen = choose(rows, fid["tolerance"], current)
    reference = {d: spec["values"][-1] for d, spec in dials(fid).items()}
    out = {"tolerance": fid["tolerance"], "chosen": chosen, "current": current, "reference": reference,
           "chain_cpu_s": {}, "campaign_h": {}}
    for name, settings in (("current", current), ("chosen", chosen), ("reference", reference)):
        cpu = chain_cpu(rows, settings)
        out["chain_cpu_s"][name] = cpu["chain"]
        out["campaign_h"][name] = campaign_hours(cpu["chain"], n_geometries, n_cores)
    return _plain(out)


def pareto_points(surrogate_rows, chain_cpu_s: float, n_validation: int, n_cores: int):
    """(design, n, campaign_h, error) of the training-set study: (n + n_validation) chains and the
    fit, over ``n_cores``; the error is the validation RMS relative error of zeta_max."""
    import pandas as pd

    df = pd.DataFrame(surrogate_rows)
    return pd.DataFrame({"design": df.design, "n": df.n, "error": df.error_zeta_max,
                         "campaign_h": ((df.n + n_validation) * chain_cpu_s / n_cores + df.fit_cpu_s) / 3600.0})


def _plain(obj):
    """Numpy scalars to Python (YAML)."""
    if isinstance(obj, dict):
        return {k: _plain(v) for k, v in obj.items()}
    return obj.item() if isinstance(obj, np.generic) else obj
