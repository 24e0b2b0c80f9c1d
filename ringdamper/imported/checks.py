"""Checks of an imported sector mesh, each before any expensive work, each raising a
:class:`~ringdamper.imported.raw.MeshFileError` that names the file, the set and the file's own
node or element labels.

Order: element types, sets, the forcing node, the length unit, the sector angle, the cyclic faces
node for node, the Jacobians, rigid-body motions left by the fixed set, the groove's orientation.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree
from skfem import FacetBasis
from skfem.quadrature import get_quadrature

from .elements import KINDS, ElementKind
from .raw import MeshFileError, RawMesh, labels_text

REQUIRED_SETS = ("fixed", "cyclic_low", "cyclic_high", "groove", "forcing")
ELEMENT_SETS = ("blade", "morph")
LINEAR_WARNING = ("linear elements lock in bending: on the built-in sector 8-node bricks are +10.9 % "
                  "high on the target mode where 27-node ones are +0.43 % (docs/model.md)")
MATCH_TOLERANCE = 1e-3   # cyclic partners: distance / smallest element edge (coordinates printed to ~6 digits pass)
ANGLE_TOLERANCE = 1e-6   # sector angle: relative to 2 pi / N
SOLID_PREFIXES = ("C3D", "tetrahedron", "hexahedron")


def element_kind(raw: RawMesh, allow_linear: bool) -> ElementKind:
    """The file's one supported solid element type; boundary (2-D) elements are dropped."""
    counts = {t: len(b[0]) for t, b in raw.blocks.items()}
    solids = {t: n for t, n in counts.items() if t.upper().startswith(tuple(p.upper() for p in SOLID_PREFIXES))}
    listing = ", ".join(f"{t}: {n}" for t, n in counts.items())
    supported = sorted(k for k, v in KINDS.items() if not v.linear)
    if not solids:
        raise MeshFileError(f"{raw.path}: no solid elements (element types {listing or 'none'}); "
                            f"supported: {supported}")
    if len(solids) > 1:
        raise MeshFileError(f"{raw.path}: mixed solid element types ({listing}): one type per sector, "
                            f"one of {supported}")
    name = next(iter(solids))
    if name.upper() not in KINDS and name not in KINDS:
        raise MeshFileError(f"{raw.path}: unsupported element type {name} ({solids[name]} elements); "
                            f"supported: {supported}")
    kind = KINDS.get(name.upper(), KINDS.get(name))
    if kind.linear and not allow_linear:
        raise MeshFileError(f"{raw.path}: linear element type {name} ({solids[name]} elements): {LINEAR_WARNING}; "
                            "set imported.allow_linear_elements: true to use them anyway")
    raw.blocks = {name: raw.blocks[name]}
    return kind


def resolve_sets(raw: RawMesh, sets: dict) -> dict[str, str]:
    """The file's name of every configured set; a missing or empty one names what the file holds."""
    out = {}
    for key in REQUIRED_SETS + ELEMENT_SETS:
        if key not in sets:
            continue
        name = raw.find_set(sets[key])
        held = ", ".join(raw.set_names()) or "none"
        if name is None:
            raise MeshFileError(f"{raw.path}: imported.sets.{key} = '{sets[key]}': no such set; the file "
                                f"holds the sets {held}")
        if key in ELEMENT_SETS and name not in raw.element_sets:
            raise MeshFileError(f"{raw.path}: imported.sets.{key} = '{sets[key]}' is a node set: an element "
                                f"set is needed; the element sets of the file are "
                                f"{', '.join(sorted(raw.element_sets)) or 'none'}")
        members = raw.element_sets[name] if key in ELEMENT_SETS else raw.nodes_of(name)
        if key in ELEMENT_SETS:
            members = np.intersect1d(members, raw.element_labels)
        else:
            members = np.intersect1d(members, raw.connectivity)
        if len(members) == 0:
            raise MeshFileError(f"{raw.path}: imported.sets.{key} = '{sets[key]}' is empty (no "
                                f"{'element' if key in ELEMENT_SETS else 'node of an element'} of the mesh); "
                                f"the file holds the sets {held}")
        out[key] = name
    return out


def forcing_node(raw: RawMesh, name: str) -> int:
    """The label of the forcing set's one node."""
    nodes = raw.nodes_of(name)
    if len(nodes) != 1:
        raise MeshFileError(f"{raw.path}: imported.sets.forcing = '{name}' must hold exactly one node; it holds "
                            f"{len(nodes)}: {labels_text(nodes)}")
    return int(nodes[0])


def length_unit(raw: RawMesh, unit: str, axis) -> None:
    """A blisk sector measures centimetres to metres: a largest radius above 20 file units in metres
    looks like millimetres, below 5 file units in millimetres like metres."""
    a = np.asarray(axis, float) / np.linalg.norm(axis)
    r = np.linalg.norm(raw.coordinates - np.outer(raw.coordinates @ a, a), axis=1)
    i = int(np.argmax(r))
    where = f"node {raw.node_labels[i]} lies {r[i]:.6g} {unit} from the axis"
    if unit == "m" and r[i] > 20.0:
        raise MeshFileError(f"{raw.path}: imported.length_unit = 'm' but {where}: the coordinates look like "
                            "millimetres; set imported.length_unit: mm")
    if unit == "mm" and r[i] < 5.0:
        raise MeshFileError(f"{raw.path}: imported.length_unit = 'mm' but {where}: the coordinates look like "
                            "metres; set imported.length_unit: m")


def _polar(x: np.ndarray) -> np.ndarray:
    return np.arctan2(x[:, 1], x[:, 0])


def sector_angle(path, low: np.ndarray, high: np.ndarray, n_sectors: int, names) -> None:
    """The cyclic faces (model coordinates, axis Z) must be 2 pi / N apart about the axis: the mean
    polar angle of the high face minus that of the low face, both measured from the low face's mean
    direction (a rotation adds its angle to every node's)."""
    ref = np.arctan2(np.sin(_polar(low)).mean(), np.cos(_polar(low)).mean())
    rel = [np.angle(np.exp(1j * (_polar(x) - ref))).mean() for x in (low, high)]
    angle, target = rel[1] - rel[0], 2 * np.pi / n_sectors
    if abs(angle - target) > ANGLE_TOLERANCE * target:
        guess = 2 * np.pi / angle if angle > 0 else float("nan")
        raise MeshFileError(f"{path}: the cyclic faces '{names[0]}' -> '{names[1]}' are {np.degrees(angle):.6g} deg "
                            f"apart about the axis, but imported.n_sectors = {n_sectors} needs "
                            f"360/{n_sectors} = {360 / n_sectors:.6g} deg (the faces' angle fits "
                            f"n_sectors = {guess:.4g}; or the axis or the sets are wrong)")


def cyclic_partners(mesh, low: np.ndarray, high: np.ndarray, n_sectors: int, h: float, names, unit_scale) -> np.ndarray:
    """High-face partner of every low-face node: R(2 pi / N) x_low = x_high within MATCH_TOLERANCE h.
    Up to ten unmatched nodes are listed with their file coordinates and the distance to the nearest
    high-face node."""
    path = names[2]
    if len(low) != len(high):
        raise MeshFileError(f"{path}: the cyclic faces do not match node for node: '{names[0]}' has {len(low)} "
                            f"nodes, '{names[1]}' {len(high)}")
    a = 2 * np.pi / n_sectors
    rot = np.array([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1.0]])
    x = mesh.nodes
    dist, idx = cKDTree(x[high]).query(x[low] @ rot.T)
    tol = MATCH_TOLERANCE * h
    bad = np.flatnonzero(dist > tol)
    if len(bad) == 0 and len(np.unique(idx)) == len(idx):
        return high[idx]
    if len(bad) == 0:
        bad = np.flatnonzero(np.bincount(idx, minlength=len(high))[idx] > 1)
    file_x = x @ mesh.rotation / unit_scale      # back to the file's frame and unit
    rows = [f"node {mesh.node_label[low[i]]} at ({', '.join(f'{c:.6g}' for c in file_x[low[i]])}): nearest "
            f"'{names[1]}' node {mesh.node_label[high[idx[i]]]} is {dist[i] / unit_scale:.3g} away" for i in bad[:10]]
    raise MeshFileError(f"{path}: {len(bad)} nodes of '{names[0]}' rotated by 360/{n_sectors} deg about the axis "
                        f"have no '{names[1]}' partner within {tol / unit_scale:.3g} (1e-3 of the smallest "
                        f"element edge, file units):\n    " + "\n    ".join(rows))


def smallest_edge(mesh) -> float:
    p, e = mesh.basis.mesh.p, mesh.basis.mesh.edges
    return float(np.linalg.norm(p[:, e[0]] - p[:, e[1]], axis=0).min())


def jacobians(mesh, element_label, intorder: int, path) -> None:
    """det(dx/dxi) > 0 at the quadrature points and the corners of every element of the scikit-fem
    ``mesh`` (the file's own orientation: scikit-fem's reference vertices are the file's corners)."""
    X, _ = get_quadrature(mesh.elem.refdom, intorder)
    det = mesh._mapping().detDF(np.hstack([X, mesh.elem.refdom.p]))
    worst = det.min(axis=1)
    bad = np.flatnonzero(worst <= 0)
    if len(bad):
        raise MeshFileError(f"{path}: {len(bad)} elements have a non-positive Jacobian (inverted or "
                            f"degenerate): elements {labels_text(element_label[bad])} (smallest det "
                            f"{worst[bad].min():.3g} m^3 per reference volume); renumber their nodes in the "
                            "element type's order")


def rigid_body(mesh, fixed: np.ndarray, low, high, path, name) -> None:
    """Every part of the sector, the cyclic faces joining parts, must hold a fixed node, and the fixed
    nodes must not all lie on the axis (a rotation about it would be free)."""
    t = mesh.basis.element_dofs
    n = mesh.basis.N
    rows = np.repeat(t, t.shape[0], axis=0).ravel()
    cols = np.tile(t, (t.shape[0], 1)).ravel()
    graph = sp.coo_matrix((np.ones(len(rows) + len(low)), (np.r_[rows, low], np.r_[cols, high])), shape=(n, n))
    count, part = connected_components(graph, directed=False)
    held = np.unique(part[fixed])
    free = [c for c in range(count) if c not in held and np.any(part[t[0]] == c)]
    if free:
        elements = np.flatnonzero(part[t[0]] == free[0])
        raise MeshFileError(f"{path}: imported.sets.fixed = '{name}' leaves {len(free)} of the sector's {count} "
                            f"disconnected parts free (a rigid-body motion): e.g. elements "
                            f"{labels_text(mesh.element_label[elements])}; merge coincident nodes where parts meet "
                            "or add their clamped nodes to the set")
    r = np.hypot(*mesh.nodes[fixed, :2].T)
    if r.max() < 1e-9 * np.abs(mesh.nodes).max():
        raise MeshFileError(f"{path}: imported.sets.fixed = '{name}': every fixed node "
                            f"({labels_text(mesh.node_label[fixed])}) lies on the axis: the rotation about it is free")


def groove_faces(mesh, groove: np.ndarray, path, name) -> np.ndarray:
    """Boundary facets of the groove set; their outward normals must face the axis (n . e_r < 0)."""
    m = mesh.basis.mesh
    vertex = np.zeros(mesh.basis.N, bool)
    vertex[groove] = True
    boundary = m.boundary_facets()
    on = boundary[np.all(vertex[m.facets[:, boundary]], axis=0)]
    if len(on) == 0:
        raise MeshFileError(f"{path}: imported.sets.groove = '{name}' holds no boundary face of the mesh "
                            f"(nodes {labels_text(mesh.node_label[groove])})")
    fb = FacetBasis(m, mesh.basis.elem, facets=on, intorder=2)
    x, nrm = np.asarray(fb.global_coordinates()), np.asarray(fb.normals)
    e_r = x[:2] / np.maximum(np.hypot(x[0], x[1]), 1e-300)
    radial = np.einsum("ifq,ifq->f", nrm[:2], e_r) / nrm.shape[2]
    bad = np.flatnonzero(radial >= 0.0)
    if len(bad):
        elements = mesh.element_label[m.f2t[0, on[bad]]]
        raise MeshFileError(f"{path}: imported.sets.groove = '{name}': {len(bad)} of its {len(on)} faces face away "
                            f"from the axis (outward normal . e_r >= 0, up to {radial[bad].max():.3g}): faces of "
                            f"elements {labels_text(elements)}; the groove is the surface the ring presses "
                            "outward against, so its outward normal points to the axis")
    return on
