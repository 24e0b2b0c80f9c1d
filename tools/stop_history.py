"""A recorded adaptive campaign as small test data for the stop rule (tests/campaign/test_adaptive_estimate.py).

From a finished adaptive campaign's results folder: ``OUT.nc``, its training and validation rings with
the four surrogate outputs, point status and kappa, each training ring with the round that chose it
(0: the initial design), and ``OUT_rounds.csv``, each round's recorded predicted optimum (the stop
rule's stability test reads it). Rounds beyond the one that stopped need a campaign run with the stop
rule off (the committed data: docs/investigations/2026-12-01-stop-rule-estimate.md).

    python -m tools.stop_history RESULTS OUT
"""
from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np
import pandas as pd
import yaml

from ringdamper.campaign.adaptive.design import round_of
from ringdamper.campaign.dataset import SURROGATE_OUTPUTS
from ringdamper.io import read_netcdf, variable

KEPT = ("status", "held", "reason", *SURROGATE_OUTPUTS)


def history_dataset(results: Path):
    """The campaign's training and validation rings (dataset.nc's KEPT variables) and their round."""
    ds = read_netcdf(results / "campaign" / "dataset.nc")
    ds = ds.isel(geometry=ds.split.isin(["training", "validation"]).values)[list(KEPT)]
    chosen = [round_of(str(g)) or 0 for g in ds.geometry.values]
    ds["round"] = variable("geometry", np.array(chosen, dtype=np.int16), "1",
                           "round that chose the training ring (0: initial design; validation rings 0)")
    return ds


def rounds_table(results: Path) -> pd.DataFrame:
    """Per round: rings computed and the predicted optimum (kappa, zeta_max) the round recorded."""
    rows = []
    for path in sorted((results / "adaptive").glob("round_*.yaml"), key=lambda p: int(p.stem.split("_")[1])):
        r = yaml.safe_load(path.read_text())
        rows.append({"round": r["round"], "n_computed": r["n_computed"],
                     **{f"kappa{i + 1}": k for i, k in enumerate(r["optimum"]["kappa"])},
                     "zeta_max": r["optimum"]["zeta_max"]})
    return pd.DataFrame(rows)


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("results", type=Path, help="results folder of a finished adaptive campaign")
    parser.add_argument("out", type=Path, help="output prefix: OUT.nc and OUT_rounds.csv")
    args = parser.parse_args(argv)
    encoding = {v: {"zlib": True, "complevel": 9} for v in KEPT if v != "reason"}
    history_dataset(args.results).to_netcdf(args.out.with_suffix(".nc"), encoding=encoding)
    rounds = rounds_table(args.results)
    if len(rounds):
        rounds.to_csv(f"{args.out}_rounds.csv", index=False, float_format="%.17g")


if __name__ == "__main__":
    main()
