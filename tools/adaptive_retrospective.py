"""What the adaptive design knew round by round, judged on the validation rings afterwards.

For each listed round k of a finished adaptive campaign, the per-amplitude Kriging models are fitted
(campaign settings) on the training rings that round k fitted (the initial design and the rings chosen
by rounds < k; k = last round + 1 is the final set), then validated on the 20 validation rings exactly
as the campaign's `validation` rule does: R², RMSE and ±2σ coverage per output, the normalised
leave-one-out errors of the stop rule, and the predicted optimum. Rings chosen later never enter, so
the table shows what stopping at round k would have given
(docs/investigations/2026-12-01-adaptive-campaigns.md).

    python -m tools.adaptive_retrospective RESULTS OUT.csv [--rounds 1 3 4 5 8]
"""
from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np
import pandas as pd

from ringdamper.campaign.adaptive.design import round_of
from ringdamper.campaign.adaptive.model import normalised_loo
from ringdamper.campaign.adaptive.rounds import predicted_optimum
from ringdamper.campaign.dataset import usable_mask
from ringdamper.campaign.exploration import cube_grid
from ringdamper.campaign.kriging import KrigingSurrogate, fit_campaign
from ringdamper.campaign.validation import metrics_table, validate
from ringdamper.config import load_config
from ringdamper.io import read_netcdf

OPTIMUM_GRID = 15     # points per axis of the grid the optimum search starts from (then polished)


def round_row(dataset, mask, chosen_in, k: int, config: dict) -> dict:
    """Validation metrics, LOO errors and predicted optimum of the models round ``k`` fitted."""
    training = (dataset.split == "training").values
    keep = ~training | (chosen_in < k)
    sub, sub_mask = dataset.isel(geometry=keep), mask.isel(geometry=keep)
    fit = fit_campaign(sub, mask=sub_mask & (sub.split == "training"), settings=config["surrogate"])
    surrogate = KrigingSurrogate(fit)
    table = metrics_table(validate(fit, surrogate, sub, sub_mask))
    optimum = predicted_optimum(surrogate, cube_grid(OPTIMUM_GRID), config["exploration"]["optimum_max_level"])
    row = {"round": k, "n_training": int((sub.split == "training").sum()),
           **{f"loo_{name}": e for name, e in normalised_loo(fit).items()}}
    for name in table.index:
        for metric in ("r2", "rmse", "coverage"):
            row[f"{metric}_{name}"] = float(table.loc[name, metric])
    row.update({f"optimum_kappa{i + 1}": v for i, v in enumerate(optimum["kappa"])})
    row["optimum_zeta_max"] = optimum["zeta_max"]
    return row


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("results", type=Path, help="results folder of a finished adaptive campaign")
    parser.add_argument("out", type=Path, help="CSV to write")
    parser.add_argument("--rounds", type=int, nargs="*",
                        help="rounds to refit (default: every round; the final set is always added)")
    args = parser.parse_args(argv)
    config = load_config()
    dataset = read_netcdf(args.results / "campaign" / "dataset.nc")
    mask = usable_mask(dataset)
    last = max(int(p.stem.split("_")[1]) for p in (args.results / "adaptive").glob("round_*.yaml"))
    chosen_in = np.array([round_of(str(g)) or 0 for g in dataset.geometry.values])
    rows = [round_row(dataset, mask, chosen_in, k, config) for k in (args.rounds or range(1, last + 1))]
    rows.append(round_row(dataset, mask, chosen_in, last + 1, config))
    pd.DataFrame(rows).to_csv(args.out, index=False, float_format="%.6g")


if __name__ == "__main__":
    main()
