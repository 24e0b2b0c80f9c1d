"""The adaptive design in the report: the trace of the rounds (estimated validation errors, predicted
optimum, stop decision) and the row of the design-comparison table (training size, job time, validation
metrics, optimum), beside the ``paper`` design's row when a committed one exists.

The row is the same for either design, so a run of ``sampling.design: paper`` writes the paper row with
the same code (docs/adaptive.md says how the committed one was made).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from ...logs import read_cpu_seconds
from ..kriging import OUTPUTS
from .accuracy import ESTIMATES

METRICS = ("r2", "rmse", "coverage")  # per output, from validation_metrics.csv


def trace_table(records: list[dict]) -> pd.DataFrame:
    """One row per round: rings computed, usable, excluded; each output's relative error estimates
    (:mod:`.accuracy`, ``<estimate>_<output>``) and the rule's estimate over its tolerance
    (``ratio_<output>``); the predicted optimum (kappa, zeta_max and its std) and its changes; the stop
    decision; rings chosen."""
    rows = []
    for r in records:
        change = r["optimum_changes"][-1] if r["optimum_changes"] else {"kappa": np.nan, "zeta_max": np.nan}
        rows.append({"round": r["round"], "n_computed": r["n_computed"], "n_usable": r["n_usable"],
                     "excluded": " ".join(r["excluded"]),
                     **{f"{e}_{o}": r["estimates"][e][o] for e in ESTIMATES for o in OUTPUTS},
                     **{f"ratio_{o}": r["ratios"][o] for o in OUTPUTS},
                     **{f"optimum_kappa{i + 1}": k for i, k in enumerate(r["optimum"]["kappa"])},
                     "optimum_zeta_max": r["optimum"]["zeta_max"],
                     "optimum_zeta_max_std": r["optimum"]["zeta_max_std"],
                     "change_kappa": change["kappa"], "change_zeta_max": change["zeta_max"],
                     "stop": r["stop"], "reason": r["reason"] or "", "n_chosen": len(r["chosen"])})
    return pd.DataFrame(rows)


def job_times(benchmarks, cpu_records) -> dict:
    """The chain's cost summed over its jobs: ``job_cpu_s`` from each job's own CPU record
    (:func:`ringdamper.logs.cpu_record`, exact), ``job_wall_s`` from its Snakemake benchmark file (column
    ``s``). A job without a record (run before records existed) counts with the benchmark's sampled
    ``cpu_time``, a lower bound (docs/adaptive.md); ``sampled_jobs`` says how many did."""
    cpu = wall = 0.0
    sampled = 0
    for benchmark, record in zip(benchmarks, cpu_records, strict=True):
        table = pd.read_csv(benchmark, sep="\t")
        wall += float(table["s"].sum())
        own = read_cpu_seconds(record)
        if own is None:
            sampled += 1
            own = float(table["cpu_time"].sum())
        cpu += own
    return {"job_cpu_s": cpu, "job_wall_s": wall, "sampled_jobs": sampled}


def design_row(design: str, samples: pd.DataFrame, records: list[dict], metrics: pd.DataFrame, optimum: dict,
               check: pd.DataFrame, table3: pd.DataFrame, times: dict, reference_lu_s: float) -> pd.DataFrame:
    """The design's row of the comparison table (one-row DataFrame). ``metrics``: validation_metrics.csv
    (index output); ``optimum``: optimum.yaml; ``check``: optimum_check.csv (row ``zeta_max``);
    ``table3``: table3.csv (the forced-response reductions of the optimum against the default ring);
    ``times``: :func:`job_times` of the chain; ``reference_lu_s``: CPU seconds of the machine's reference
    LU (:mod:`ringdamper.bench.machine`), the unit of ``job_cpu_reference_lus``, the job CPU that compares
    between machines."""
    cpu = times["job_cpu_s"]
    zeta = check.set_index("quantity").loc["zeta_max"]
    row = {"design": design, "n_training": int((samples.split == "training").sum()), "rounds": len(records),
           "stop": records[-1]["reason"] if records else "", "job_cpu_s": cpu, "job_wall_s": times["job_wall_s"],
           "reference_lu_s": reference_lu_s, "job_cpu_reference_lus": cpu / reference_lu_s,
           **{f"optimum_kappa{i + 1}": k for i, k in enumerate(optimum["kappa"])},
           "zeta_max_predicted": float(zeta["predicted"]), "zeta_max_computed": float(zeta["computed"])}
    for out in OUTPUTS:
        for m in METRICS:
            row[f"{out}_{m}"] = float(metrics.loc[out, m])
    for level in table3.itertuples():
        row[f"table3_reduction_eebm_pct_{level.level}"] = float(level.reduction_eebm_pct)
        row[f"table3_reduction_frf_pct_{level.level}"] = float(level.reduction_frf_pct)
    return pd.DataFrame([row])


def comparison_table(row: pd.DataFrame, committed: Path) -> tuple[pd.DataFrame, list[str]]:
    """``row`` beside the committed row of the other design (``committed``, a design-row CSV) if it
    exists; the notes say which."""
    if committed.exists():
        other = pd.read_csv(committed)
        other = other[other.design != row.design.iloc[0]]
        return pd.concat([row, other], ignore_index=True), [f"Other design's row: {committed} (committed)."]
    return row, [f"No committed row of the other design ({committed} absent)."]
