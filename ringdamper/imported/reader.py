"""Read a sector mesh file by its suffix: Abaqus/CalculiX .inp (flat deck) or Gmsh .msh (4.1 ASCII)."""

from __future__ import annotations

from pathlib import Path

from .abaqus import read_inp
from .gmsh_msh import read_msh
from .raw import MeshFileError, RawMesh

READERS = {".inp": read_inp, ".msh": read_msh}


def read_mesh(path) -> RawMesh:
    path = Path(path)
    reader = READERS.get(path.suffix.lower())
    if reader is None:
        raise MeshFileError(f"{path}: unknown mesh format '{path.suffix}': allowed {sorted(READERS)} "
                            "(Abaqus/CalculiX input deck, Gmsh 4.1 ASCII)")
    if not path.is_file():
        raise MeshFileError(f"{path}: no such mesh file")
    return reader(path)
