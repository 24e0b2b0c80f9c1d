"""Two results trees hold the same numbers, to the bit: every NetCDF's variables and coordinates
(values, not attributes: those carry wall times and provenance), every CSV table and every YAML file.
Logs, benchmarks, figures and the report are not compared, nor the columns of measured job times
(MEASURED_COLUMNS) a table may carry.

    python -m tools.compare_results RESULTS_A RESULTS_B
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd
import xarray as xr
import yaml

COMPARED = ("*.nc", "*.csv", "*.yaml")
SKIPPED = ("logs", "benchmarks")
# the design row's summed job times and the reference LU timed by its rule (and their ratio)
MEASURED_COLUMNS = ("job_cpu_s", "job_wall_s", "reference_lu_s", "job_cpu_reference_lus")


def files(root: Path) -> set[str]:
    """Paths (relative to ``root``) of the compared files."""
    return {str(p.relative_to(root)) for pattern in COMPARED for p in root.rglob(pattern)
            if p.relative_to(root).parts[0] not in SKIPPED}


def same_arrays(a, b) -> bool:
    a, b = np.asarray(a), np.asarray(b)
    if a.shape != b.shape or a.dtype != b.dtype:
        return False
    return bool(np.array_equal(a, b, equal_nan=a.dtype.kind in "fc"))


def file_differences(a: Path, b: Path) -> list[str]:
    """What differs between two files of the same kind (empty when they hold the same numbers)."""
    if a.suffix == ".nc":
        with xr.open_dataset(a) as da, xr.open_dataset(b) as db:
            names = set(da.variables) | set(db.variables)
            return [name for name in sorted(names) if name not in da.variables or name not in db.variables
                    or not same_arrays(da[name].values, db[name].values)]
    if a.suffix == ".csv":
        ta, tb = (pd.read_csv(p).drop(columns=list(MEASURED_COLUMNS), errors="ignore") for p in (a, b))
        return [] if ta.equals(tb) else ["table"]
    return [] if yaml.safe_load(a.read_text()) == yaml.safe_load(b.read_text()) else ["content"]


def differences(root_a, root_b) -> list[str]:
    """One line per missing or differing file of two results trees."""
    root_a, root_b = Path(root_a), Path(root_b)
    fa, fb = files(root_a), files(root_b)
    out = [f"only in {root_a}: {p}" for p in sorted(fa - fb)] + [f"only in {root_b}: {p}" for p in sorted(fb - fa)]
    for rel in sorted(fa & fb):
        diff = file_differences(root_a / rel, root_b / rel)
        if diff:
            out.append(f"{rel}: {', '.join(diff)} differ")
    return out


def main(argv: list[str]) -> int:
    root_a, root_b = argv
    diff = differences(root_a, root_b)
    print("\n".join(diff) if diff else
          f"{len(files(Path(root_a)))} files (NetCDF arrays, CSV, YAML) identical to the bit")
    return 1 if diff else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
