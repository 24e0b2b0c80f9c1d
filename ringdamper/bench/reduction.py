"""Benchmark of the reduction stage (rule ``reduced``): CPU seconds per part for real rings.

Per ring, as :func:`ringdamper.reduction.stage.run_reduced` does it: the model (mesh and assembly),
Craig–Bampton (constraint modes, fixed-interface modes, mass products: ``CraigBampton.cpu_s``),
Mead + interface reduction of harmonics 0..H, the modal bases and the dataset written to NetCDF. The
imports of the rule script are timed in a fresh interpreter. CPU time of this process
(``time.process_time``), so that other work on a shared machine moves it less than the wall time.
:func:`run` returns the figures; it asserts nothing (speed is measured, never asserted).
"""
from __future__ import annotations

import subprocess
import sys
import tempfile
import time
from pathlib import Path

#: The default ring and one other (kappa3 = +1, a reference ring of the campaign).
RINGS = {"default": (0.0, 0.0, 0.0), "kappa3=+1": (0.0, 0.0, 1.0)}

#: What scripts/reduced.py imports.
RULE_IMPORTS = "import ringdamper.io, ringdamper.logs, ringdamper.reduction.stage"


def import_cpu_s() -> float:
    """CPU seconds of the rule script's imports in a fresh interpreter (interpreter start included)."""
    code = f"import time; {RULE_IMPORTS}; print(time.process_time())"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    return float(out.stdout.split()[-1])


def time_ring(config: dict, kappa) -> dict:
    """CPU seconds per part of the reduction of ring ``kappa``, and the sizes."""
    from ringdamper.fem.model import build_model
    from ringdamper.geometry.sector import build_sector
    from ringdamper.io import write_netcdf
    from ringdamper.reduction.craig_bampton import craig_bampton
    from ringdamper.reduction.partition import partition
    from ringdamper.reduction.reduced import modal_basis, reduce_harmonics, reduced_dataset
    from ringdamper.reduction.stage import reduction_sizes

    sizes = reduction_sizes(config)
    out = {}
    t = time.process_time()
    model = build_model(build_sector(config, kappa), config)
    out["model_s"] = time.process_time() - t
    t = time.process_time()
    part = partition(model)
    cb = craig_bampton(model.K, model.M, part.boundary, part.interior, sizes["n_fi"])
    out["craig_bampton_s"] = time.process_time() - t
    out.update({f"craig_bampton_{k}_s": v for k, v in cb.cpu_s.items()})
    t = time.process_time()
    rs = reduce_harmonics(model, part, cb, config["operation"]["engine_order"],
                          range(config["reduction"]["n_harmonics"] + 1), sizes["n_if"])
    out["mead_interface_s"] = time.process_time() - t
    t = time.process_time()
    bases = [modal_basis(rh, rs.response_index) for rh in rs.harmonics]
    out["modal_bases_s"] = time.process_time() - t
    t = time.process_time()
    with tempfile.TemporaryDirectory() as tmp:
        write_netcdf(reduced_dataset(rs, kappa, bases), Path(tmp) / "reduced.nc", config)
    out["dataset_file_s"] = time.process_time() - t
    out["dofs"] = rs.dof_counts
    return out


def run(config: dict, rings: dict = RINGS) -> dict:
    """Import CPU seconds, then per ring the parts and their sum with the imports."""
    imports = import_cpu_s()
    out = {"imports_s": imports}
    for label, kappa in rings.items():
        row = time_ring(config, kappa)
        parts = ("model_s", "craig_bampton_s", "mead_interface_s", "modal_bases_s", "dataset_file_s")
        row["total_with_imports_s"] = imports + sum(row[k] for k in parts)
        out[label] = {"kappa": list(kappa), **row}
    return out
