"""Reader of flat Abaqus / CalculiX input decks (.inp): *NODE, *ELEMENT, *NSET, *ELSET (with
GENERATE), *SURFACE (TYPE=ELEMENT, faces S1..S6) and *INCLUDE; every other keyword is skipped.

Node and element labels are kept as written. A deck with *PART, *ASSEMBLY or *INSTANCE holds its
mesh in local part coordinates placed by instance transforms; it is refused with how to flatten it.
Set names are kept as written (Abaqus compares them ignoring case; so does :meth:`RawMesh.find_set`).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .elements import ABAQUS
from .raw import MeshFileError, RawMesh

FLATTEN = ("write the deck flat: in Abaqus/CAE tick Model > Edit Attributes > 'Do not use parts and "
           "assemblies in input files' (or export the assembly's mesh as an orphan mesh), so that *NODE and "
           "*ELEMENT stand at the top level in global coordinates")


def _keyword(line: str) -> tuple[str, dict]:
    parts = [p.strip() for p in line[1:].split(",")]
    params = {}
    for p in parts[1:]:
        key, _, value = p.partition("=")
        if key:
            params[key.strip().upper()] = value.strip()
    return parts[0].upper(), params


def _lines(path: Path):
    """(line number, text) of the deck without comments, *INCLUDE files read in place."""
    for number, raw in enumerate(path.read_text(errors="replace").splitlines(), start=1):
        line = raw.strip()
        if not line or line.startswith("**"):
            continue
        if line.startswith("*") and _keyword(line)[0] == "INCLUDE":
            yield from _lines((path.parent / _keyword(line)[1]["INPUT"]).resolve())
            continue
        yield path, number, line


def _ints(text: str) -> list[int]:
    return [int(float(t)) for t in text.split(",") if t.strip()]


def _members(values: list[str], generate: bool, known: dict) -> list[int]:
    """Labels of a set's data lines: labels, names of sets already defined, or start, end, step."""
    if generate:
        out = []
        for line in values:
            start, end, *step = _ints(line)
            out += list(range(start, end + 1, step[0] if step else 1))
        return out
    out = []
    for token in (t.strip() for line in values for t in line.split(",")):
        if not token:
            continue
        if token.lstrip("-").isdigit():
            out.append(int(token))
        elif token.upper() in known:
            out += list(known[token.upper()])
    return out


def _blocks(path: Path) -> list[tuple[str, dict, list[str], int]]:
    """(keyword, parameters, data lines, line number) of every keyword block."""
    out = []
    for file, number, line in _lines(path):
        if line.startswith("*"):
            name, params = _keyword(line)
            if name in ("PART", "ASSEMBLY", "INSTANCE"):
                raise MeshFileError(f"{file}: line {number}: *{name}: a deck with parts and assemblies is not "
                                    f"read; {FLATTEN}")
            out.append((name, params, [], number))
        elif out:
            out[-1][2].append(line)
    return out


def _element_rows(kind_nodes: int, lines: list[str]) -> np.ndarray:
    """(e, 1 + nodes) rows; a row may continue on the next line (Abaqus: a line ending with ',')."""
    tokens, rows = [], []
    for line in lines:
        tokens += _ints(line)
        if len(tokens) >= 1 + kind_nodes and not line.rstrip().endswith(","):
            rows.append(tokens[:1 + kind_nodes])
            tokens = []
    return np.array(rows, dtype=np.int64).reshape(-1, 1 + kind_nodes)


def _surface_nodes(lines, elsets, blocks, path) -> list[int]:
    """Node labels of an element-based *SURFACE: data lines 'element or elset, Sk'."""
    nodes = []
    for line in lines:
        target, face = [t.strip() for t in line.split(",")[:2]]
        labels = [int(target)] if target.isdigit() else list(elsets.get(target.upper(), []))
        for etype, (elabels, conn) in blocks.items():
            kind = ABAQUS[etype]
            k = int(face.upper().lstrip("S")) - 1
            local = [j for j, c in enumerate(kind.nodes) if set(c) <= set(kind.faces[k])]
            rows = np.isin(elabels, labels)
            nodes += conn[rows][:, local].ravel().tolist()
    if not nodes:
        raise MeshFileError(f"{path}: *SURFACE data {lines[:2]} name no element of the deck")
    return nodes


def read_inp(path: Path) -> RawMesh:
    """Read a flat deck; every element type of the file is kept (the checks refuse several)."""
    nodes, blocks, nsets, elsets, surfaces, names = [], {}, {}, {}, {}, {}
    for name, params, lines, number in _blocks(path):
        if name == "NODE":
            rows = np.array([[float(t) for t in ln.split(",")[:4]] for ln in lines]).reshape(-1, 4)
            nodes.append(rows)
            if "NSET" in params:
                nsets.setdefault(params["NSET"].upper(), []).extend(rows[:, 0].astype(int).tolist())
                names.setdefault(params["NSET"].upper(), params["NSET"])
        elif name == "ELEMENT":
            etype = params.get("TYPE", "?").upper()
            n = ABAQUS[etype].n_nodes if etype in ABAQUS else max(len(_ints(lines[0])) - 1, 1)
            rows = _element_rows(n, lines)
            old = blocks.get(etype, (np.zeros(0, np.int64), np.zeros((0, n), np.int64)))
            blocks[etype] = (np.concatenate([old[0], rows[:, 0]]), np.vstack([old[1], rows[:, 1:]]))
            if "ELSET" in params:
                elsets.setdefault(params["ELSET"].upper(), []).extend(rows[:, 0].tolist())
                names.setdefault(params["ELSET"].upper(), params["ELSET"])
        elif name in ("NSET", "ELSET"):
            key = params.get(name, "")
            target = nsets if name == "NSET" else elsets
            members = _members(lines, "GENERATE" in params, target)
            if name == "NSET" and "ELSET" in params:   # the nodes of an element set
                members = _elset_nodes(elsets.get(params["ELSET"].upper(), []), blocks)
            target.setdefault(key.upper(), []).extend(members)
            names.setdefault(key.upper(), key)
        elif name == "SURFACE" and params.get("TYPE", "ELEMENT").upper() == "ELEMENT":
            surfaces[params["NAME"].upper()] = _surface_nodes(lines, elsets, blocks, path)
            names.setdefault(params["NAME"].upper(), params["NAME"])
    if not nodes:
        raise MeshFileError(f"{path}: no *NODE block: not a mesh deck")
    table = np.vstack(nodes)

    def named(sets):
        return {names[k]: np.asarray(v, dtype=np.int64) for k, v in sets.items()}

    return RawMesh(path=path, node_labels=table[:, 0].astype(np.int64), coordinates=table[:, 1:4],
                   blocks=blocks, node_sets=named(nsets), element_sets=named(elsets), surfaces=named(surfaces))


def _elset_nodes(labels, blocks) -> list[int]:
    return [int(n) for elabels, conn in blocks.values() for n in conn[np.isin(elabels, labels)].ravel()]
