"""What the adaptive design knew round by round, judged on the validation rings afterwards.

For each listed round k of a finished adaptive campaign, the per-amplitude Kriging models are fitted
(campaign settings) on the training rings that round k fitted (the initial design and the rings chosen
by rounds < k; k = last round + 1 is the final set), then validated on the 20 validation rings exactly
as the campaign's `validation` rule does: R², RMSE and ±2σ coverage per output, the predicted optimum,
and the training-side estimates of the validation error (:mod:`ringdamper.campaign.adaptive.accuracy`,
relative to the predicted spread S_o) beside the validation RMSE relative to the same spread
(``rel_rmse_*``) and to the validation rings' own spread (``val_rel_rmse_*``, pooled within
amplitudes). ``heldback_*``: the RMSE, relative to S_o, of round k's models at the rings round k chose
(computed afterwards): the held-back estimate round k + 1 could read. Rings chosen later never enter, so
the table shows what stopping at round k would have given
(docs/investigations/2026-12-01-adaptive-campaigns.md).

    python -m tools.adaptive_retrospective RESULTS OUT.csv [--rounds 1 3 4 5 8] [--config config.yaml]
        [--subsets 28 32 36 40] [--splits 30 8] [--no-rounds]
"""
from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np
import pandas as pd

from ringdamper.campaign.adaptive.accuracy import domain_points, estimates
from ringdamper.campaign.adaptive.design import round_of
from ringdamper.campaign.adaptive.model import RoundModels
from ringdamper.campaign.adaptive.replay import pooled_spread
from ringdamper.campaign.adaptive.rounds import predicted_optimum
from ringdamper.campaign.dataset import kappa, usable_mask
from ringdamper.campaign.exploration import backbones, cube_grid
from ringdamper.campaign.kriging import OUTPUTS, KrigingSurrogate, fit_campaign
from ringdamper.campaign.validation import metrics_table, validate
from ringdamper.config import load_config
from ringdamper.io import read_netcdf

OPTIMUM_GRID = 15     # points per axis of the grid the optimum search starts from (then polished)


def rmse_at(surrogate, dataset, mask, rings: np.ndarray) -> dict:
    """output -> RMSE of the surrogate's median at the usable points of the geometries ``rings`` (bool)."""
    if not rings.any():
        return {o: np.nan for o in OUTPUTS}
    sub, ok = dataset.isel(geometry=rings), mask.isel(geometry=rings).values
    bb = backbones(surrogate, kappa(sub), OUTPUTS, with_std=False)
    return {o: float(np.sqrt(np.mean((sub[o].values - bb.mean[o].T)[ok] ** 2))) for o in OUTPUTS}


def fit_row(dataset, mask, keep: np.ndarray, config: dict, points: np.ndarray, held_back: np.ndarray) -> dict:
    """Validation metrics, error estimates and predicted optimum of the models fitted on the training
    rings of ``keep`` (bool over the geometries; the validation rings are always validated), and the
    relative RMSE at the geometries ``held_back`` (bool)."""
    keep = keep | (dataset.split == "validation").values
    sub, sub_mask = dataset.isel(geometry=keep), mask.isel(geometry=keep)
    fit = fit_campaign(sub, mask=sub_mask & (sub.split == "training"), settings=config["surrogate"])
    surrogate = KrigingSurrogate(fit)
    table = metrics_table(validate(fit, surrogate, sub, sub_mask))
    optimum = predicted_optimum(surrogate, cube_grid(OPTIMUM_GRID), config["exploration"]["optimum_max_level"])
    est = estimates(RoundModels(fit, surrogate), points)
    held = rmse_at(surrogate, dataset, mask, held_back)
    val = (sub.split == "validation").values
    ok = sub_mask.isel(geometry=val).values
    row = {"n_training": int((sub.split == "training").sum())}
    for name in OUTPUTS:
        spread = est["spread"][name]
        row[f"spread_{name}"] = spread
        row.update({f"{e}_{name}": est[e][name] for e in est if e != "spread"})
        row[f"heldback_{name}"] = held[name] / spread
        row[f"rel_rmse_{name}"] = float(table.loc[name, "rmse"]) / spread
        vals = sub[name].isel(geometry=val).transpose("geometry", "amplitude").values
        row[f"val_rel_rmse_{name}"] = float(table.loc[name, "rmse"]) / pooled_spread(vals, ok)
        for metric in ("r2", "rmse", "coverage"):
            row[f"{metric}_{name}"] = float(table.loc[name, metric])
    row.update({f"optimum_kappa{i + 1}": v for i, v in enumerate(optimum["kappa"])})
    row["optimum_zeta_max"] = optimum["zeta_max"]
    return row


def round_row(dataset, mask, chosen_in, k: int, config: dict, points: np.ndarray) -> dict:
    """:func:`fit_row` of the models round ``k`` fitted (the initial design and the rings of rounds < k),
    held back: the rings round ``k`` chose."""
    training = (dataset.split == "training").values
    return {"round": k, **fit_row(dataset, mask, training & (chosen_in < k), config, points,
                                  training & (chosen_in == k))}


def subset_rows(dataset, mask, config: dict, points: np.ndarray, sizes, seed: int) -> list[dict]:
    """:func:`fit_row` of random subsets of the training rings, one per size in ``sizes`` (the rest of
    the training rings held back): more cases of the estimates against the validation error."""
    rng = np.random.default_rng(seed)
    training = np.flatnonzero((dataset.split == "training").values)
    rows = []
    for n in sizes:
        keep = np.zeros(dataset.sizes["geometry"], bool)
        keep[rng.choice(training, n, replace=False)] = True
        held_back = (dataset.split == "training").values & ~keep
        rows.append({"round": -1, **fit_row(dataset, mask, keep, config, points, held_back)})
    return rows


def split_rows(dataset, mask, config: dict, points: np.ndarray, n_train: int, n_splits: int, seed: int) -> list[dict]:
    """:func:`fit_row` of ``n_splits`` random splits of every computed ring (training and validation):
    ``n_train`` rings train, the others validate (round -2): cases of the estimates against the
    validation error that need no ring beyond those computed."""
    rng = np.random.default_rng([seed, n_train])
    rows = []
    for _ in range(n_splits):
        split = np.full(dataset.sizes["geometry"], "validation", dtype=object)
        split[rng.choice(dataset.sizes["geometry"], n_train, replace=False)] = "training"
        relabelled = dataset.assign_coords(split=("geometry", split))
        none = np.zeros(dataset.sizes["geometry"], bool)
        rows.append({"round": -2, **fit_row(relabelled, mask, split == "training", config, points, none)})
    return rows


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("results", type=Path, help="results folder of a finished adaptive campaign")
    parser.add_argument("out", type=Path, help="CSV to write")
    parser.add_argument("--rounds", type=int, nargs="*",
                        help="rounds to refit (default: every round; the final set is always added)")
    parser.add_argument("--config", type=Path, default=None, help="campaign configuration (default config.yaml)")
    parser.add_argument("--subsets", type=int, nargs="*", default=[],
                        help="also fit random subsets of the training rings of these sizes (round -1)")
    parser.add_argument("--splits", type=int, nargs=2, default=[0, 0], metavar=("N_TRAIN", "N_SPLITS"),
                        help="also fit N_SPLITS random splits of all computed rings, N_TRAIN training (round -2)")
    parser.add_argument("--no-rounds", action="store_true", help="skip the rounds (only subsets and splits)")
    args = parser.parse_args(argv)
    config = load_config(args.config) if args.config else load_config()
    dataset = read_netcdf(args.results / "campaign" / "dataset.nc")
    mask = usable_mask(dataset)
    last = max((int(p.stem.split("_")[1]) for p in (args.results / "adaptive").glob("round_*.yaml")), default=0)
    chosen_in = np.array([round_of(str(g)) or 0 for g in dataset.geometry.values])
    points = domain_points(config["sampling"]["seed"])
    rows = [] if args.no_rounds else [round_row(dataset, mask, chosen_in, k, config, points)
                                      for k in [*(args.rounds or range(1, last + 1)), last + 1]]
    rows += subset_rows(dataset, mask, config, points, args.subsets, config["sampling"]["seed"])
    rows += split_rows(dataset, mask, config, points, *args.splits, config["sampling"]["seed"])
    pd.DataFrame(rows).to_csv(args.out, index=False, float_format="%.6g")


if __name__ == "__main__":
    main()
