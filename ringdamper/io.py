"""File contracts between the stages (docs/design.md §4), in one place.

NetCDF through xarray: SI units, and every data variable and coordinate carries ``units`` and
``long_name`` (checked on write). Meshes and fields for ParaView through meshio (VTU, 27-node bricks
written as VTK triquadratic hexahedra).
"""

from __future__ import annotations

import contextlib
import functools
import glob
import hashlib
import json
import os
import subprocess
from pathlib import Path

import numpy as np
import xarray as xr
import yaml


class ContractError(ValueError):
    """A dataset violates the file contract (missing units or long_name)."""


def variable(dims, data, units: str, long_name: str, **attrs):
    """(dims, data, attrs) tuple for xarray with the mandatory attributes."""
    return (dims, np.asarray(data), {"units": units, "long_name": long_name, **attrs})


def declared_dataset(kind: str, declared: dict, values: dict, coords: dict, attrs: dict) -> xr.Dataset:
    """A stage file from its declaration ``declared`` (name -> (dims, units, long_name)), the one
    place its variables are listed: ``values`` must hold exactly those variables."""
    if set(values) != set(declared):
        raise ValueError(f"{kind} variables {sorted(values)} differ from {sorted(declared)}")
    data = {k: variable(dims, values[k], units, long_name) for k, (dims, units, long_name) in declared.items()}
    return xr.Dataset(data, coords=coords, attrs=attrs)


def nan_values(declared: dict, sizes: dict) -> dict:
    """Every variable of a declaration, all NaN, with the dimension ``sizes``: a failed geometry's."""
    return {k: np.full([sizes[d] for d in np.atleast_1d(dims)], np.nan) for k, (dims, _, _) in declared.items()}


def check_contract(ds: xr.Dataset) -> None:
    missing = [name for name in list(ds.data_vars) + list(ds.coords)
               if not {"units", "long_name"} <= set(ds[name].attrs)]
    if missing:
        raise ContractError(f"variables without units/long_name: {missing}")


@functools.lru_cache(maxsize=1)
def software_provenance() -> dict:
    """Versions of the package and of numpy, scipy and openturns, and the git commit of the source
    tree when it is a git work tree (``unknown`` otherwise; ``+dirty`` with uncommitted changes)."""
    from importlib.metadata import version

    source = Path(__file__).resolve().parent.parent
    try:
        git = functools.partial(subprocess.run, capture_output=True, text=True, timeout=10, check=True,
                                cwd=source)
        commit = git(["git", "rev-parse", "HEAD"]).stdout.strip()
        commit += "+dirty" if git(["git", "status", "--porcelain", "--untracked-files=no"]).stdout else ""
    except (OSError, subprocess.SubprocessError):
        commit = "unknown"
    return {"ringdamper_version": version("ringdamper"), "git_commit": commit,
            **{f"{lib}_version": version(lib) for lib in ("numpy", "scipy", "openturns")}}


def provenance(config: dict | None = None) -> dict:
    """Provenance attributes of a NetCDF file: :func:`software_provenance`, and with ``config`` (the
    configuration sections the file depends on, as its rule passes them) their names and the SHA-256
    of their canonical JSON."""
    attrs = dict(software_provenance())
    if config is not None:
        text = json.dumps(config, sort_keys=True, separators=(",", ":"))
        attrs.update(config_sections=" ".join(config),
                     config_sha256=hashlib.sha256(text.encode()).hexdigest())
    return attrs


@contextlib.contextmanager
def written_whole(path):
    """A temporary path beside ``path`` (same folder and suffix) to write into; renamed to ``path``
    (``os.replace``, atomic on POSIX) once the write has returned. A process killed while writing
    leaves at ``path`` the previous file, or none, never half a file, and its temporary, which the
    next write of ``path`` removes; a write that raises leaves no temporary behind."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    for stale in path.parent.glob(f".{glob.escape(path.stem)}.*.part{glob.escape(path.suffix)}"):
        stale.unlink(missing_ok=True)  # left by a killed writer
    part = path.with_name(f".{path.stem}.{os.getpid()}.part{path.suffix}")
    try:
        yield part
        os.replace(part, path)
    finally:
        part.unlink(missing_ok=True)


def write_netcdf(ds: xr.Dataset, path, config: dict | None = None) -> None:
    """Write ``ds`` (contract checked) with its :func:`provenance` attributes, whole or not at all
    (:func:`written_whole`); a rule script passes the configuration sections its rule declares, so
    that the file records the hash of what it depends on (kappa, for a geometry's file, is the
    dataset's own ``kappa`` attribute)."""
    check_contract(ds)
    with written_whole(path) as part:
        ds.assign_attrs(provenance(config)).to_netcdf(part, engine="netcdf4")


class InputFileError(ValueError):
    """An input file is unreadable or is not the stage file it should be."""


def unreadable(path, err: OSError) -> InputFileError:
    """The error of a NetCDF file that netCDF4/HDF5 cannot open (``err``), naming it."""
    return InputFileError(f"{path}: truncated or not a NetCDF file ({err})")


#: What each stage file must hold for its readers: variables, and attributes (a failed geometry's
#: files hold them too, NaN).
REQUIRED = {
    "reduced": (("omega2", "contact_shape_real", "contact_shape_imag", "response_shape_real",
                 "response_shape_imag"), ("n_sectors", "engine_order")),
    "static": (("N0", "gap", "kn", "kt"), ("kappa", "status")),
    "dnnm": (("omega0", "frequency", "zeta", "gamma", "q_res_z", "status"), ("kappa",)),
}


def read_netcdf(path, kind: str | None = None) -> xr.Dataset:
    """The dataset of ``path``, loaded. An unreadable file (truncated, or not NetCDF) raises
    :class:`InputFileError` naming it; with ``kind`` (a key of :data:`REQUIRED`) so does a file
    that lacks a variable or attribute of that stage file."""
    try:
        with xr.open_dataset(path, engine="netcdf4") as ds:
            ds = ds.load()
    except FileNotFoundError:
        raise
    except OSError as err:
        raise unreadable(path, err) from err
    if kind is not None:
        variables, attrs = REQUIRED[kind]
        missing = [a for a in attrs if a not in ds.attrs]
        if not missing:
            missing = [v for v in variables if v not in ds.variables]
        if missing:
            raise InputFileError(f"{path}: not a ringdamper {kind}.nc: {missing[0]} missing")
    return ds


def write_yaml(data: dict, path) -> None:
    """``data`` as YAML in its insertion order, whole or not at all (:func:`written_whole`)."""
    with written_whole(path) as part, open(part, "w") as fh:
        yaml.safe_dump(data, fh, sort_keys=False)


def write_vtu(model, path, point_data: dict | None = None, cell_data: dict | None = None) -> None:
    """Mesh of a SectorModel (nodes = the model's nodes) with named fields, for ParaView, whole or
    not at all (:func:`written_whole`)."""
    from skfem.io.meshio import to_meshio

    cells = {k: [np.asarray(v)] for k, v in (cell_data or {}).items()}
    with written_whole(path) as part:
        to_meshio(model.geometry.mesh, point_data=point_data or {}, cell_data=cells).write(part)


def mesh_fields(model) -> tuple[dict, dict]:
    """Point and cell fields of the mesh file: body, contact pair id (the pair weighing the node most),
    local normal, part id."""
    n = len(model.nodes)
    pair_id = model.pairs.pair_of_node(n)
    normal = np.where((pair_id >= 0)[:, None], model.pairs.frame[pair_id, 0], 0.0)
    forcing = np.zeros(n, dtype=int)
    forcing[model.tip_node] = 1
    return ({"body": model.node_body, "pair_id": pair_id, "contact_normal": normal,
             "forcing_node": forcing},
            {"part": model.geometry.part})


def write_csv(rows: list[dict], path) -> None:
    """Rows of a study as CSV: the union of the rows' keys as columns, floats to 6 significant digits,
    lists as space-separated values."""
    import csv

    keys = []
    for r in rows:
        keys += [k for k in r if k not in keys]

    def cell(v):
        if isinstance(v, float):
            return f"{v:.6g}"
        if isinstance(v, (list, tuple, np.ndarray)):
            return " ".join(str(cell(x)) for x in np.asarray(v).tolist())
        return v

    Path(path).parent.mkdir(parents=True, exist_ok=True)
    with open(path, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=keys)
        w.writeheader()
        for r in rows:
            w.writerow({k: cell(v) for k, v in r.items()})
