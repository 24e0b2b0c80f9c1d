"""The performance table: the current figures of the campaign and of ``make bench``, read from their
outputs and written as one generated page (``docs/performance.md``), which the documentation quotes
instead of copying figures by hand.

Sources, all under one results folder:

* the campaign's own tables: ``tables/design_row.csv`` (the design's row of the design comparison,
  :func:`ringdamper.campaign.adaptive.report.design_row`: training rings, rounds, summed job CPU and
  wall time, the reference LU) and ``samples.csv`` (the validation rings);
* its jobs' records: one Snakemake benchmark file ``benchmarks/<job>.tsv`` per job, one CPU record
  ``logs/<job>.cpu.json`` per job (:func:`ringdamper.logs.cpu_record`) and the timestamps of the
  jobs' logs (the campaign's wall time is the span from the first record to the last);
* ``make bench``'s files ``benchmarks/<name>.json`` (:mod:`ringdamper.bench.run`), each with the
  machine it ran on (:mod:`ringdamper.bench.machine`).

A figure whose source is absent is left out of the table (a campaign without ``make bench``, or the
reverse). Run from the repository root::

    python -m ringdamper.performance --results results --out results/tables/performance.md
"""
from __future__ import annotations

import argparse
import json
import re
from datetime import datetime
from pathlib import Path

import numpy as np
import pandas as pd

#: the timestamp that opens each record of a job's log (:func:`ringdamper.logs.to_file`)
LOG_TIME = re.compile(r"^(\d{4}-\d{2}-\d{2} \d{2}:\d{2}:\d{2}),(\d{3}) ", flags=re.M)
COLUMNS = ("section", "quantity", "value", "unit", "source")


def _row(section: str, quantity: str, value, unit: str, source: str) -> dict:
    return dict(zip(COLUMNS, (section, quantity, value, unit, source)))


def campaign_rows(results: Path) -> list[dict]:
    """The campaign's figures: its design's row, its validation rings, its jobs and their times."""
    results = Path(results)
    rows = []
    row_file = results / "tables" / "design_row.csv"
    if row_file.exists():
        row = pd.read_csv(row_file).iloc[0]
        src = "tables/design_row.csv"
        rows += [_row("campaign", "design", str(row["design"]), "", src),
                 _row("campaign", "training rings", int(row["n_training"]), "", src),
                 _row("campaign", "adaptive rounds", int(row["rounds"]), "", src),
                 _row("campaign", "job CPU", float(row["job_cpu_s"]), "s", src),
                 _row("campaign", "job wall time, summed", float(row["job_wall_s"]), "s", src),
                 _row("campaign", "reference LU, campaign's machine", float(row["reference_lu_s"]), "s", src),
                 _row("campaign", "job CPU in reference LUs", float(row["job_cpu_reference_lus"]), "", src),
                 _row("campaign", "optimum's zeta_max, computed", float(row["zeta_max_computed"]), "", src)]
    samples = results / "samples.csv"
    if samples.exists():
        split = pd.read_csv(samples)["split"]
        rows.append(_row("campaign", "validation rings", int((split == "validation").sum()), "", "samples.csv"))
    jobs = sorted(p.relative_to(results / "benchmarks").with_suffix("")
                  for p in (results / "benchmarks").rglob("*.tsv"))
    if jobs:
        rows.append(_row("campaign", "jobs", len(jobs), "", "benchmarks/**/*.tsv"))
    span = log_span_seconds([results / "logs" / f"{job}.log" for job in jobs])
    if span is not None:
        rows.append(_row("campaign", "wall time, first to last record of the jobs' logs", span / 60, "min",
                         "logs/**/*.log"))
    rows += _stage_rows(results, "dnnm", "dNNM")
    rows += _stage_rows(results, "reduced", "reduction")
    rows += _stage_rows(results, "static", "static contact")
    return rows


def _stage_rows(results: Path, stage: str, name: str) -> list[dict]:
    """Median and largest job CPU of one per-geometry stage, from its jobs' CPU records."""
    records = sorted((results / "logs" / stage).glob("*.cpu.json"))
    if not records:
        return []
    cpu = np.array([json.loads(p.read_text())["cpu_s"] for p in records])
    src = f"logs/{stage}/*.cpu.json"
    return [_row("campaign", f"{name} job CPU, median of {len(cpu)}", float(np.median(cpu)), "s", src),
            _row("campaign", f"{name} job CPU, largest", float(cpu.max()), "s", src)]


def log_span_seconds(logs) -> float | None:
    """Seconds from the first to the last timestamped record over the job logs ``logs`` (those that
    exist), or None with fewer than two records."""
    stamps = []
    for path in (Path(p) for p in logs if Path(p).exists()):
        for date, ms in LOG_TIME.findall(path.read_text(errors="replace")):
            stamps.append(datetime.fromisoformat(date).timestamp() + int(ms) / 1000)
    return max(stamps) - min(stamps) if len(stamps) > 1 else None


def bench_rows(benchmarks: Path) -> list[dict]:
    """``make bench``'s figures: the machine, the per-geometry chain of the default ring, the dNNM of
    the median and hard rings, the reduction, the surrogates and each benchmark's peak memory."""
    found = {p.stem: json.loads(p.read_text()) for p in sorted(Path(benchmarks).glob("*.json"))}
    rows = []
    if not found:
        return rows
    machine = next(iter(found.values()))["machine"]
    src = "benchmarks/*.json: machine"
    rows += [_row("machine", "CPU", machine["cpu_model"], "", src),
             _row("machine", "reference LU, bench's machine", machine["reference_lu_s"], "s", src)]
    if "load_average_1min" in machine:
        rows.append(_row("machine", "load average when the bench started", machine["load_average_1min"], "", src))
    chain = found.get("geometry_chain", {})
    src = "benchmarks/geometry_chain.json"
    for key, quantity in (("chain_default_H_s", "chain mesh → static → reduced → dNNM, default ring, wall"),
                          ("mesh_model_s", "mesh and model, wall"), ("static_s", "static contact, wall"),
                          ("reduced_s", "reduction, wall")):
        if key in chain:
            rows.append(_row("bench", quantity, chain[key], "s", f"{src}: {key}"))
    for key in sorted(k for k in chain if re.fullmatch(r"dnnm_H\d+_s", k)):
        rows.append(_row("bench", f"dNNM + E-EBM, default ring, H = {key[6:-2]}, wall", chain[key], "s",
                         f"{src}: {key}"))
    curves = chain.get("frf_table3", [])
    if curves:
        seconds = [c["cpu_seconds"] for c in curves]
        rows += [_row("bench", f"Table 3 forced response CPU, default ring, least of {len(seconds)}", min(seconds),
                      "s", f"{src}: frf_table3.cpu_seconds"),
                 _row("bench", "Table 3 forced response CPU, default ring, most", max(seconds), "s",
                      f"{src}: frf_table3.cpu_seconds")]
    rows += _dnnm_rows(found.get("dnnm", {}))
    if "modal_stage_s" in found.get("fe_model", {}):
        rows.append(_row("bench", "modal stage, default ring, wall", found["fe_model"]["modal_stage_s"], "s",
                         "benchmarks/fe_model.json: modal_stage_s"))
    synthetic = found.get("static_synthetic", {})
    for element in ("Q2", "Q1"):
        for method in ("penalty", "lagrange"):
            if method in synthetic.get(element, {}):
                rows.append(_row("bench", f"static solver, two blocks, {element}, {method}",
                                 synthetic[element][method]["solve_s"], "s",
                                 f"benchmarks/static_synthetic.json: {element}.{method}.solve_s"))
    for name, quantity in (("reduction", "reduction benchmark, whole, wall"),
                           ("surrogate", "Kriging + grid + Sobol, wall"),
                           ("library", "NLvib examples 05 and 07, wall")):
        if "total_wall_s" in found.get(name, {}):
            rows.append(_row("bench", quantity, found[name]["total_wall_s"], "s",
                             f"benchmarks/{name}.json: total_wall_s"))
    peaks = {name: b["peak_rss_mb"] for name, b in found.items() if "peak_rss_mb" in b}
    if peaks:
        worst = max(peaks, key=peaks.get)
        rows.append(_row("bench", f"peak memory, largest ({worst})", peaks[worst], "MB",
                         f"benchmarks/{worst}.json: peak_rss_mb"))
    return rows


def _dnnm_rows(dnnm: dict) -> list[dict]:
    src = "benchmarks/dnnm.json"
    rows = []
    if "default" in dnnm:
        rows += [_row("bench", "dNNM CPU, default ring", dnnm["default"]["cpu_s"], "s", f"{src}: default"),
                 _row("bench", "dNNM CPU, default ring, in reference LUs", dnnm["default"]["cpu_reference_lus"],
                      "", f"{src}: default")]
    if "median_cpu_s" in dnnm:
        rows += [_row("bench", "dNNM CPU, median of the median-cost rings", dnnm["median_cpu_s"], "s",
                      f"{src}: median_cpu_s"),
                 _row("bench", "dNNM CPU, slowest ring over that median", dnnm["cpu_max_over_median"], "×",
                      f"{src}: cpu_max_over_median")]
    return rows


def performance_table(results) -> pd.DataFrame:
    """Every figure of the campaign in ``results`` and of ``make bench`` in ``results/benchmarks``."""
    results = Path(results)
    return pd.DataFrame(campaign_rows(results) + bench_rows(results / "benchmarks"), columns=COLUMNS)


def _format(value) -> str:
    if isinstance(value, (float, np.floating)):
        return f"{value:.0f}" if abs(value) >= 1000 else f"{value:.4g}"
    return str(value)


def markdown(table: pd.DataFrame) -> str:
    """The table as the generated page: a note that it is generated, then one table per section."""
    lines = ["# Performance: the current figures (generated)", "",
             "Generated by `python -m ringdamper.performance` (`make performance`) from the campaign's "
             "tables and job records and from `make bench`'s files; do not edit by hand. "
             "Seconds compare only on one machine (the `machine` rows; docs/design.md §8); rows marked wall are "
             "wall-clock seconds, which a loaded machine stretches, the others CPU seconds.", ""]
    for section, part in table.groupby("section", sort=False):
        lines += [f"## {section}", "", "| quantity | value | unit | source |", "|---|---|---|---|"]
        lines += [f"| {r.quantity} | {_format(r.value)} | {r.unit} | `{r.source}` |" for r in part.itertuples()]
        lines.append("")
    return "\n".join(lines)


def read_markdown(text: str) -> dict[str, str]:
    """quantity -> value as printed, read back from a page written by :func:`markdown`."""
    return {m[1]: m[2] for m in re.finditer(r"^\| ([^|]+?) \| ([^|]*?) \| [^|]*\| `[^`]*` \|$", text, flags=re.M)}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--results", default="results", help="the results folder (default: results)")
    parser.add_argument("--out", default="results/tables/performance.md")
    args = parser.parse_args(argv)
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(markdown(performance_table(args.results)))
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
