"""Write a scikit-fem mesh with named node and element sets as a flat Abaqus deck (.inp) or a Gmsh
4.1 ASCII mesh (.msh) in the element type's own node order (:mod:`.elements`); labels are
index + 1. In the .msh file each node set is a physical group of point elements on one point
entity, each element set a physical group of one volume entity (the elements outside every set form
one more volume entity).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .elements import ElementKind, skfem_corner_subsets, skfem_vertex_order

MIRROR = {"hex": (4, 5, 6, 7, 0, 1, 2, 3), "tet": (0, 2, 1, 3)}   # file corner -> its mirror image


def file_connectivity(basis, kind: ElementKind) -> np.ndarray:
    """(e, n) node indices of each element in the file type's node order, each element positively
    oriented (an element whose scikit-fem map has a negative Jacobian, which scikit-fem accepts, is
    written mirrored: bottom and top faces swapped, or a tetrahedron's corners 2 and 3)."""
    vertex = skfem_vertex_order(kind)                      # scikit-fem vertex -> file corner
    names = [frozenset(int(vertex[v]) for v in s) for s in skfem_corner_subsets(basis.elem)]
    conn = basis.element_dofs[[names.index(frozenset(c)) for c in kind.nodes]].T
    mirror = MIRROR[kind.shape]
    file_names = [frozenset(n) for n in kind.nodes]
    flipped = [file_names.index(frozenset(mirror[c] for c in n)) for n in kind.nodes]
    centre = np.full((3, 1), 0.25 if kind.shape == "tet" else 0.5)
    det = basis.mesh._mapping().detDF(centre)[:, 0]
    conn[det < 0] = conn[det < 0][:, flipped]
    return conn


def write_inp(path, nodes, conn, kind: ElementKind, node_sets: dict, element_sets: dict) -> None:
    lines = ["*HEADING", f" {Path(path).name}", "*NODE"]
    lines += [f"{i + 1}, {x:.17g}, {y:.17g}, {z:.17g}" for i, (x, y, z) in enumerate(nodes)]
    lines.append(f"*ELEMENT, TYPE={kind.name}, ELSET=EALL")
    for e, row in enumerate(conn):
        labels = [str(e + 1)] + [str(n + 1) for n in row]
        chunks = [labels[i:i + 16] for i in range(0, len(labels), 16)]  # at most 16 entries a line
        lines += [", ".join(c) + ("," if k < len(chunks) - 1 else "") for k, c in enumerate(chunks)]
    for keyword, sets in (("NSET", node_sets), ("ELSET", element_sets)):
        for name, members in sets.items():
            lines.append(f"*{keyword}, {keyword}={name}")
            labels = [str(m + 1) for m in members]
            lines += [", ".join(labels[i:i + 16]) for i in range(0, len(labels), 16)]
    Path(path).write_text("\n".join(lines) + "\n")


def write_msh(path, nodes, conn, gmsh_type: int, node_sets: dict, element_sets: dict) -> None:
    rest = np.setdiff1d(np.arange(len(conn)), np.concatenate([*element_sets.values(), []]).astype(int))
    volumes = list(element_sets.items()) + ([("", rest)] if len(rest) else [])
    groups = [(0, name) for name in node_sets] + [(3, name) for name, _ in element_sets.items()]
    out = ["$MeshFormat", "4.1 0 8", "$EndMeshFormat", "$PhysicalNames", str(len(groups))]
    out += [f'{dim} {k + 1} "{name}"' for k, (dim, name) in enumerate(groups)]
    out += ["$EndPhysicalNames", "$Entities", f"{len(node_sets)} 0 0 {len(volumes)}"]
    out += [f"{k + 1} 0 0 0 1 {k + 1}" for k in range(len(node_sets))]
    out += [f"{v + 1} 0 0 0 0 0 0 {int(name != '')} {len(node_sets) + v + 1 if name else ''} 0".replace("  ", " ")
            for v, (name, _) in enumerate(volumes)]
    out += ["$EndEntities", "$Nodes", f"1 {len(nodes)} 1 {len(nodes)}", f"3 1 0 {len(nodes)}"]
    out += [str(i + 1) for i in range(len(nodes))] + [f"{x:.17g} {y:.17g} {z:.17g}" for x, y, z in nodes]
    n_point = sum(len(m) for m in node_sets.values())
    out += ["$EndNodes", "$Elements", f"{len(node_sets) + len(volumes)} {n_point + len(conn)} 1 {n_point + len(conn)}"]
    tag = 0
    for k, members in enumerate(node_sets.values()):
        out.append(f"0 {k + 1} 15 {len(members)}")
        out += [f"{len(conn) + tag + j + 1} {m + 1}" for j, m in enumerate(members)]
        tag += len(members)
    for v, (_, members) in enumerate(volumes):
        out.append(f"3 {v + 1} {gmsh_type} {len(members)}")
        out += [" ".join(str(x + 1) for x in [e, *conn[e]]) for e in members]
    out.append("$EndElements")
    Path(path).write_text("\n".join(out) + "\n")
