"""The adaptive design over seeds of its initial design: run each seed's campaign up to its validation,
then chart the stop round, the training rings and each output's validation RMSE against the paper
design's (docs/adaptive/paper_design_row.csv).

``run`` computes seed S (``sampling.adaptive.initial_seed``) into RESULTS/seed-S, the same workflow and
configuration as ``make campaign`` but for that one key, up to the validation metrics (the rounds, their
rings, the dataset, the stopping round's models and their validation; not the forced responses, the
Sobol' indices or the report; ``--until rounds``: the rounds and their rings only). Every ring the
campaign REUSE has finished at exactly a parse-time ring's shape parameters (the reference rings of
the initial design and the 20 validation rings, which do not depend on the initial design's seed) is
copied from it, with the modal stage the rings' dNNMs are normalised by: those jobs' outputs depend on
the ring's kappa and the physics sections only, so the files are the ones the seed would compute. A
Snakemake dry run first checks that none of the copied rings' jobs would run again. ``collect`` reads
each results folder (round records and surrogate/validation_metrics.csv) into one table and its chart.

    python -m tools.adaptive_seeds run --seed 1 --reuse results --out results/seeds [--until rounds] [--dry-run]
    python -m tools.adaptive_seeds collect results results/seeds/seed-1 ... --csv T.csv --png F.png
"""
from __future__ import annotations

import argparse
import os
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd
import yaml

from ringdamper.campaign.kriging import OUTPUTS
from ringdamper.campaign.sampling import make_samples
from ringdamper.config import load_config
from ringdamper.io import read_netcdf

DEFAULT_GID = "t000"  # the default ring, first of the reference rings in every initial design
PAPER_ROW = Path(__file__).parents[1] / "docs" / "adaptive" / "paper_design_row.csv"
RING_STAGES = ("static", "reduced", "dnnm")
# the outputs of the modal stage and of the default ring's stuck normalisation (rules modal, stuck_default)
MODAL_FILES = ("modal", "figures/nd_diagram.png", "figures/campbell.png", "figures/modes_target_nd.png",
               "logs/modal.log", "logs/modal.cpu.json", "benchmarks/modal.tsv", "logs/stuck_default.log",
               "logs/stuck_default.cpu.json", "benchmarks/stuck_default.tsv")
# the target of each stage: every round and its rings (the sample table lists them), then the validation
STAGES = {"rounds": "samples.csv", "validation": "surrogate/validation_metrics.csv"}
SNAKEMAKE_JOB = re.compile(r"^\s*rule (\w+):\s*$")  # indented in a group job
WILDCARDS = re.compile(r"^\s*wildcards: gid=(\S+)")


def seed_config(seed: int, results: Path) -> Path:
    """results/seed.yaml: the configuration file (over config.yaml) of seed ``seed`` into ``results``
    (Snakemake's --config would pass the seed as a string)."""
    path = results / "seed.yaml"
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(yaml.safe_dump({"results": str(results), "sampling": {"adaptive": {"initial_seed": seed}}}))
    return path


def reusable_rings(seed: int, reuse: Path, results: Path) -> list[str]:
    """gids of the parse-time rings of seed ``seed`` (this configuration otherwise) that the campaign
    ``reuse`` finished (its dNNM job's benchmark written) at exactly the seed's kappa (the ``kappa``
    attribute of each stage's file) and ``results`` does not hold yet."""
    config = load_config()
    config["sampling"]["adaptive"]["initial_seed"] = seed
    rings = []
    for row in make_samples(config["sampling"]).itertuples():
        folder = reuse / "geometry" / row.gid
        if (results / "geometry" / row.gid).exists() or not (reuse / "benchmarks" / "dnnm" / f"{row.gid}.tsv").exists():
            continue
        kappa = [row.kappa1, row.kappa2, row.kappa3]
        if all(np.array_equal(read_netcdf(folder / f"{stage}.nc").attrs["kappa"], kappa) for stage in RING_STAGES):
            rings.append(row.gid)
    return rings


def copy_rings(gids: list[str], reuse: Path, results: Path) -> None:
    """Copy the rings ``gids`` (files, logs, benchmarks of each stage) and the modal stage (unless
    there already) from ``reuse`` to ``results``, every copied file given the time of the copy: no
    input is newer than an output of the copied jobs, and every output is newer than this checkout's
    rule scripts (Snakemake reruns a script's job whose outputs are older than the script)."""
    paths = [f for f in MODAL_FILES if not (results / f).exists()] + [f"geometry/{g}" for g in gids]
    paths += [f"{kind}/{stage}/{g}{ext}" for g in gids for stage in RING_STAGES
              for kind, ext in (("logs", ".log"), ("logs", ".cpu.json"), ("benchmarks", ".tsv"))]
    for rel in paths:
        src, dst = reuse / rel, results / rel
        if not src.exists():
            raise FileNotFoundError(f"{src}: the finished campaign {reuse} lacks it")
        dst.parent.mkdir(parents=True, exist_ok=True)
        if src.is_dir():
            shutil.copytree(src, dst, dirs_exist_ok=True)
        else:
            shutil.copyfile(src, dst)
    now = time.time()
    for rel in paths:
        for path in [results / rel, *(results / rel).rglob("*")]:
            os.utime(path, (now, now))


def snakemake(seed: int, results: Path, cores: int, until: str, *extra: str) -> subprocess.CompletedProcess:
    """Snakemake (of this interpreter's environment) on the target of stage ``until`` of seed ``seed``."""
    exe = Path(sys.executable).with_name("snakemake")
    cmd = [str(exe), str(results / STAGES[until]), "--workflow-profile", "profiles/default",
           "--cores", str(cores), *extra, "--configfile", str(seed_config(seed, results))]
    return subprocess.run(cmd, capture_output="-n" in extra, text=True, check=True)


def planned_ring_jobs(dry_run: str) -> set[tuple[str, str]]:
    """(rule, gid) of every ring job a Snakemake dry run's output lists."""
    jobs, rule = set(), None
    for line in dry_run.splitlines():
        if m := SNAKEMAKE_JOB.match(line):
            rule = m.group(1)
        elif (m := WILDCARDS.match(line)) and rule in RING_STAGES:
            jobs.add((rule, m.group(1)))
    return jobs


def run(seed: int, reuse: Path, out: Path, cores: int, until: str, dry_run: bool = False) -> Path:
    """Seed ``seed`` into ``out``/seed-<seed> up to ``until`` (a key of STAGES; module docstring;
    ``dry_run``: copy and check only); returns that folder."""
    if seed == 0:
        raise ValueError("--seed 0 is the default initial design: the campaign of `make campaign`")
    results = out / f"seed-{seed}"
    gids = reusable_rings(seed, reuse, results)
    if not (results / "geometry" / DEFAULT_GID).exists() and DEFAULT_GID not in gids:
        raise RuntimeError(f"{reuse} has not finished the default ring {DEFAULT_GID}, which the modal stage "
                           "and every dNNM's normalisation come from: run again once it has")
    copy_rings(gids, reuse, results)
    rerun = sorted(j for j in planned_ring_jobs(snakemake(seed, results, cores, until, "-n").stdout) if j[1] in gids)
    if rerun:
        raise RuntimeError(f"Snakemake would compute the copied rings again: {rerun}")
    print(f"seed {seed}: {len(gids)} rings copied from {reuse}: {gids}", flush=True)
    if not dry_run:
        snakemake(seed, results, cores, until)
    return results


def seed_row(results: Path) -> dict:
    """Seed, stop round and reason, training rings, the rule's last estimate / tolerance, predicted
    optimum and validation RMSE per output of the campaign in ``results``."""
    records = [yaml.safe_load(p.read_text()) for p in
               sorted((results / "adaptive").glob("round_*.yaml"), key=lambda p: int(p.stem.split("_")[1]))]
    last = records[-1]
    metrics = pd.read_csv(results / "surrogate" / "validation_metrics.csv").set_index("output")
    seed = re.fullmatch(r"seed-(\d+)", results.name)
    row = {"seed": int(seed.group(1)) if seed else 0, "stop_round": last["round"], "reason": last["reason"],
           "n_training": last["n_computed"], "worst_ratio": last["worst_ratio"],
           **{f"optimum_kappa{i + 1}": k for i, k in enumerate(last["optimum"]["kappa"])},
           "zeta_max_predicted": last["optimum"]["zeta_max"]}
    row.update({f"{o}_rmse": float(metrics.loc[o, "rmse"]) for o in OUTPUTS})
    return row


def collect(folders: list[Path], csv: Path, png: Path) -> pd.DataFrame:
    """The seeds' table (``seed_row`` of each folder, and each RMSE over the paper design's) and chart."""
    table = pd.DataFrame([seed_row(f) for f in folders]).sort_values("seed")
    paper = pd.read_csv(PAPER_ROW).iloc[0]
    for o in OUTPUTS:
        table[f"{o}_ratio"] = table[f"{o}_rmse"] / paper[f"{o}_rmse"]
    table.to_csv(csv, index=False, float_format="%.6g")
    chart(table, png)
    return table


def chart(table: pd.DataFrame, png: Path) -> None:
    """Training rings (stop round written on each bar) and validation RMSE over the paper design's, per seed."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4), constrained_layout=True)
    x = np.arange(len(table))
    bars = left.bar(x, table.n_training, color=["C0" if r == "converged" else "C7" for r in table.reason])
    for bar, (_, r) in zip(bars, table.iterrows()):
        left.annotate(f"round {r.stop_round}\n{r.reason}", (bar.get_x() + bar.get_width() / 2, bar.get_height()),
                      ha="center", va="bottom", fontsize=8)
    left.axhline(pd.read_csv(PAPER_ROW).n_training.iloc[0], color="k", ls=":", label="paper design")
    left.set(xticks=x, xticklabels=[f"seed {s}" for s in table.seed], ylabel="training rings at the stop",
             ylim=(0, 110))
    left.legend(loc="upper right", fontsize=8)
    for i, o in enumerate(OUTPUTS):
        right.plot(x + (i - 1.5) * 0.08, table[f"{o}_ratio"], "o", label=o)
        right.plot([x[0] - 0.3, x[-1] + 0.3], [table[f"{o}_ratio"].median()] * 2, color=f"C{i}", lw=0.8)
    right.axhline(1.0, color="k", lw=0.8)
    right.axhline(1.1, color="r", ls="--", lw=0.8, label="target 1.1")
    right.set(xticks=x, xticklabels=[f"seed {s}" for s in table.seed],
              ylabel="validation RMSE / paper design's (lines: medians)")
    right.legend(fontsize=8, ncol=2)
    fig.savefig(png, dpi=120)
    plt.close(fig)


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)
    p_run = sub.add_parser("run", help="compute one seed's campaign up to its validation")
    p_run.add_argument("--seed", type=int, required=True, help="sampling.adaptive.initial_seed (not 0)")
    p_run.add_argument("--reuse", type=Path, required=True, help="results folder of a finished campaign")
    p_run.add_argument("--out", type=Path, required=True, help="folder of the seeds' results folders")
    p_run.add_argument("--cores", type=int, default=2)
    p_run.add_argument("--until", choices=list(STAGES), default="validation",
                       help="rounds: the rounds and their rings only (REUSE's validation rings unfinished)")
    p_run.add_argument("--dry-run", action="store_true", help="copy the shared rings and check, do not run")
    p_collect = sub.add_parser("collect", help="table and chart of finished seeds' results folders")
    p_collect.add_argument("folders", type=Path, nargs="+", help="results folders (seed-<S>, or the default's)")
    p_collect.add_argument("--csv", type=Path, required=True)
    p_collect.add_argument("--png", type=Path, required=True)
    args = parser.parse_args(argv)
    if args.command == "run":
        run(args.seed, args.reuse, args.out, args.cores, args.until, args.dry_run)
    else:
        print(collect(args.folders, args.csv, args.png).to_string())


if __name__ == "__main__":
    main()
