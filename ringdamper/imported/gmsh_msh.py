"""Reader of Gmsh meshes in the ASCII format 4.1 (.msh): nodes and elements with their own tags,
physical groups as sets (a volume group: an element set; a point, curve or surface group: the node
set of its elements). An entity in several physical groups belongs to every one of them.

Gmsh reference manual, *MSH file format* (version 4.1): sections $MeshFormat, $PhysicalNames,
$Entities, $Nodes, $Elements; the others are skipped.
"""

from __future__ import annotations

from collections import defaultdict
from pathlib import Path

import numpy as np

from .elements import GMSH
from .raw import MeshFileError, RawMesh


def _sections(path: Path) -> dict[str, list[str]]:
    out, name = {}, None
    for line in path.read_text(errors="replace").splitlines():
        if line.startswith("$End"):
            name = None
        elif line.startswith("$"):
            name = line[1:].strip()
            out[name] = []
        elif name is not None:
            out[name].append(line)
    return out


def _entity_groups(lines: list[str]) -> dict[tuple[int, int], list[int]]:
    """(dim, entity tag) -> physical tags, from $Entities."""
    counts = [int(x) for x in lines[0].split()]
    groups, row = {}, 1
    for dim, count in enumerate(counts):
        for _ in range(count):
            values = lines[row].split()
            row += 1
            tag, skip = int(values[0]), 4 if dim == 0 else 7
            n_phys = int(values[skip])
            groups[(dim, tag)] = [int(v) for v in values[skip + 1:skip + 1 + n_phys]]
    return groups


def _nodes(lines: list[str]) -> tuple[np.ndarray, np.ndarray]:
    n_blocks = int(lines[0].split()[0])
    labels, coords, row = [], [], 1
    for _ in range(n_blocks):
        _, _, parametric, n = (int(v) for v in lines[row].split())
        labels += [int(v) for v in lines[row + 1:row + 1 + n]]
        coords += [[float(v) for v in ln.split()[:3]] for ln in lines[row + 1 + n:row + 1 + 2 * n]]
        row += 1 + 2 * n
    return np.array(labels, dtype=np.int64), np.array(coords).reshape(-1, 3)


def _elements(lines: list[str]):
    """Blocks (dim, entity tag, type, element tags, node tags)."""
    n_blocks = int(lines[0].split()[0])
    out, row = [], 1
    for _ in range(n_blocks):
        dim, entity, etype, n = (int(v) for v in lines[row].split())
        table = np.array([[int(v) for v in ln.split()] for ln in lines[row + 1:row + 1 + n]], dtype=np.int64)
        out.append((dim, entity, etype, table[:, 0], table[:, 1:]))
        row += 1 + n
    return out


def read_msh(path: Path) -> RawMesh:
    try:
        text_head = path.read_bytes()[:200].decode("ascii")
    except UnicodeDecodeError:
        text_head = ""
    sec = _sections(path) if text_head.startswith("$MeshFormat") else {}
    fmt = sec.get("MeshFormat", [""])[0].split()
    if len(fmt) < 2 or fmt[0] != "4.1" or fmt[1] != "0":
        raise MeshFileError(f"{path}: not an ASCII Gmsh 4.1 mesh ($MeshFormat {' '.join(fmt[:2]) or 'missing'}); "
                            "save it with Mesh.MshFileVersion = 4.1 and Mesh.Binary = 0")
    names = {}
    for ln in sec.get("PhysicalNames", [])[1:]:
        dim, tag, name = ln.split(maxsplit=2)
        names[(int(dim), int(tag))] = name.strip().strip('"')
    groups = _entity_groups(sec["Entities"]) if "Entities" in sec else {}
    labels, coords = _nodes(sec["Nodes"])
    blocks, node_sets, element_sets = {}, defaultdict(list), defaultdict(list)
    for dim, entity, etype, tags, conn in _elements(sec["Elements"]):
        for phys in groups.get((dim, entity), []):
            name = names.get((dim, phys), str(phys))
            (element_sets[name].extend(tags.tolist()) if dim == 3 else node_sets[name].extend(conn.ravel().tolist()))
        if dim != 3:
            continue
        key = GMSH[etype].name if etype in GMSH else f"gmsh type {etype}"
        old = blocks.get(key, (np.zeros(0, np.int64), np.zeros((0, conn.shape[1]), np.int64)))
        blocks[key] = (np.concatenate([old[0], tags]), np.vstack([old[1], conn]))
    return RawMesh(path=path, node_labels=labels, coordinates=coords, blocks=blocks,
                   node_sets={k: np.array(v) for k, v in node_sets.items()},
                   element_sets={k: np.array(v) for k, v in element_sets.items()})
