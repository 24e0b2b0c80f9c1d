"""Recompute a results tree's nonlinear outputs with the code at hand and compare them to the bit: every
geometry's dnnm.nc and the forced responses (frf/<gid>/gamma_<level>.nc, frf/table3.csv).

    python -m tools.recompute_nonlinear BASELINE SCRATCH [--config config.yaml] [--jobs 1] [--gids a,b]
                                        [--skip-dnnm] [--skip-frf]

BASELINE is only read: its inputs (reduced.nc, static.nc, modal/stuck_default.yaml, frf/levels.yaml) and
outputs are first copied to SCRATCH/baseline, so a campaign still writing it is not disturbed. The dnnm.nc
of every geometry that has all three files is recomputed into SCRATCH/new by
:func:`ringdamper.nonlinear.stage.dnnm_stage` (what the rule dnnm's script calls), the forced-response
curves by :func:`ringdamper.campaign.forced_check.forced_curve` from the baseline's dnnm.nc (as
scripts/frf_curve.py) and Table 3 from them (as scripts/table3.py). Each process runs single-threaded, as
the campaign's jobs do (BLAS threads change the rounding). Files are compared by
:func:`tools.compare_results.file_differences`: every variable's values. The NetCDF attributes are
compared too but only reported: the provenance of the code (``git_commit``) and the wall times
(:data:`MEASURED`) differ by design. Prints one line per file and the counts; exits 1 if any file's
values differ.
"""
from __future__ import annotations

import argparse
import json
import shutil
import sys
from pathlib import Path

import yaml

from ringdamper.workers import single_threaded, worker_pool
from tools.compare_results import file_differences

#: the configuration sections of the rules dnnm and frf_curve (workflow/rules/common.smk: DNNM, FORCED)
DNNM_SECTIONS = ("material", "geometry", "mesh", "operation", "contact", "static", "reduction", "modal", "dnnm")
FORCED_SECTIONS = DNNM_SECTIONS + ("frf",)
GEOMETRY_FILES = ("reduced.nc", "static.nc", "dnnm.nc")
#: attributes that measure the run, not its result
MEASURED = ("wall_time_s",)


def sections(config: dict, names) -> dict:
    """The configuration restricted to the sections ``names``, keys sorted: a rule's ``params.config``
    (workflow/rules/common.smk ``sections``)."""
    return json.loads(json.dumps({name: config[name] for name in names if name in config}, sort_keys=True))


def attribute_differences(a: Path, b: Path) -> list[str]:
    """The attributes of two NetCDF files that differ, but for :data:`MEASURED` (none for other files)."""
    if a.suffix != ".nc":
        return []
    import xarray as xr

    with xr.open_dataset(a) as da, xr.open_dataset(b) as db:
        names = (set(da.attrs) | set(db.attrs)) - set(MEASURED)
        return sorted(k for k in names if str(da.attrs.get(k)) != str(db.attrs.get(k)))


def copy_baseline(baseline: Path, copy: Path, gids: list[str] | None) -> list[str]:
    """Copy the files the recomputation reads and compares to ``copy``; the geometries that have all of
    :data:`GEOMETRY_FILES`."""
    done = []
    for folder in sorted((baseline / "geometry").iterdir()):
        if (gids and folder.name not in gids) or not all((folder / f).exists() for f in GEOMETRY_FILES):
            continue
        (copy / "geometry" / folder.name).mkdir(parents=True, exist_ok=True)
        for name in GEOMETRY_FILES:
            shutil.copy2(folder / name, copy / "geometry" / folder.name / name)
        done.append(folder.name)
    for rel in ["modal/stuck_default.yaml", "frf/levels.yaml", "frf/table3.csv",
                *(str(p.relative_to(baseline)) for p in sorted(baseline.glob("frf/*/gamma_*.nc")))]:
        if (baseline / rel).exists():
            (copy / rel).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(baseline / rel, copy / rel)
    return done


def recompute_dnnm(base: Path, new: Path, gid: str, config: dict) -> str:
    """dnnm.nc of geometry ``gid`` from the copied inputs in ``base``, written to ``new``."""
    single_threaded()
    from ringdamper.io import read_netcdf, write_netcdf
    from ringdamper.nonlinear.stage import dnnm_stage

    folder = base / "geometry" / gid
    static = read_netcdf(folder / "static.nc", "static")
    normalisation = yaml.safe_load((base / "modal" / "stuck_default.yaml").read_text())
    ds = dnnm_stage(read_netcdf(folder / "reduced.nc", "reduced"), static, config,
                    list(static.attrs["kappa"]), normalisation)
    out = new / "geometry" / gid / "dnnm.nc"
    out.parent.mkdir(parents=True, exist_ok=True)
    write_netcdf(ds, out, config)
    return str(out.relative_to(new))


def recompute_curve(base: Path, new: Path, curve: Path, config: dict) -> str:
    """One forced-response curve (frf/<gid>/gamma_<level>.nc) from the copied inputs, as frf_curve.py."""
    single_threaded()
    from ringdamper.campaign.forced_check import EEBMBackbone, forced_curve
    from ringdamper.io import read_netcdf, write_netcdf
    from ringdamper.nonlinear.stage import contacts_from_static, structure_from_reduced

    gid, level = curve.parent.name, int(curve.stem.split("_")[1])
    gamma = yaml.safe_load((base / "frf" / "levels.yaml").read_text())["gamma_N"][level - 1]
    folder = base / "geometry" / gid
    dnnm = read_netcdf(folder / "dnnm.nc", "dnnm")
    H, nt = int(dnnm.attrs["n_harmonics"]), int(dnnm.attrs["n_time_samples"])
    ds = forced_curve(structure_from_reduced(read_netcdf(folder / "reduced.nc", "reduced"), H),
                      contacts_from_static(read_netcdf(folder / "static.nc", "static"), config["contact"],
                                           dnnm.attrs["friction_law"]),
                      EEBMBackbone.from_dnnm(dnnm), gamma, H=H, nt=nt,
                      zeta_s=float(dnnm.attrs["structural_damping_ratio"]), band=config["frf"]["frequency_band"],
                      omega_reference=float(dnnm.attrs["omega_stuck_default"]))
    ds.attrs.update(gid=gid, level=level, kappa=dnnm.attrs["kappa"])
    out = new / curve.relative_to(base)
    out.parent.mkdir(parents=True, exist_ok=True)
    write_netcdf(ds, out, config)
    return str(out.relative_to(new))


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("baseline", type=Path)
    parser.add_argument("scratch", type=Path)
    parser.add_argument("--config", type=Path, default=Path("config.yaml"))
    parser.add_argument("--jobs", type=int, default=1)
    parser.add_argument("--gids", default="", help="comma-separated geometry ids (default: all)")
    parser.add_argument("--skip-dnnm", action="store_true")
    parser.add_argument("--skip-frf", action="store_true")
    args = parser.parse_args(argv)
    config = yaml.safe_load(args.config.read_text())
    base, new = args.scratch / "baseline", args.scratch / "new"
    gids = copy_baseline(args.baseline, base, [g for g in args.gids.split(",") if g])
    jobs = [] if args.skip_dnnm else [(recompute_dnnm, base, new, gid, sections(config, DNNM_SECTIONS))
                                      for gid in gids]
    if not args.skip_frf:
        jobs += [(recompute_curve, base, new, curve, sections(config, FORCED_SECTIONS))
                 for curve in sorted(base.glob("frf/*/gamma_*.nc"))]
    with worker_pool(args.jobs) as pool:
        written = [f.result() for f in [pool.submit(*job) for job in jobs]]
    if not args.skip_frf and (base / "frf" / "table3.csv").exists():
        written.append(write_table3(base, new))
    different = 0
    for rel in written:
        diff = file_differences(base / rel, new / rel)
        different += bool(diff)
        attrs = attribute_differences(base / rel, new / rel)
        note = f" (attributes that differ: {', '.join(attrs)})" if attrs else ""
        print(f"{rel}: {'identical' if not diff else 'DIFFERS in ' + ', '.join(diff)}{note}", flush=True)
    print(f"{len(written)} files compared, {len(written) - different} identical to the bit "
          "(variables' values; attributes such as provenance hashes and wall times not compared)")
    return 1 if different else 0


def write_table3(base: Path, new: Path) -> str:
    """frf/table3.csv from the recomputed curves, as scripts/table3.py: the ring ``optimum`` (the rule's
    OPTIMUM_GID) against the other ring of frf/ (the default), each in level order."""
    from ringdamper.campaign.forced_check import table3
    from ringdamper.io import read_netcdf

    folders = sorted(p.name for p in (new / "frf").iterdir() if p.is_dir())
    rings = {"optimum": "optimum", "default": next(g for g in folders if g != "optimum")}
    curves = {ring: [read_netcdf(p) for p in sorted((new / "frf" / gid).glob("gamma_*.nc"),
                                                    key=lambda p: int(p.stem.split("_")[1]))]
              for ring, gid in rings.items()}
    out = new / "frf" / "table3.csv"
    table3(curves).to_csv(out, index=False, float_format="%.6g")
    return str(out.relative_to(new))


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
