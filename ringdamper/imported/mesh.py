"""The scikit-fem mesh and scalar basis of an imported sector, in SI units with the rotation axis on Z.

Nodes are re-numbered to scikit-fem's DoF order; ``node_label[i]`` is the file's label of node i.
Quadratic elements are isoparametric: every file node is a node of the mesh, matched to its
scikit-fem local DoF by the corners it lies between (:mod:`.elements`). A 20-node brick is carried
on a 27-node mesh whose face and centre points are the serendipity map's own (x_face = 1/2 sum of
the face's mid-edge nodes - 1/4 sum of its corners; x_centre = 1/4 sum of the 12 mid-edge nodes -
1/4 sum of the 8 corners), so the 27-node geometry map equals the 20-node one (the serendipity
space lies inside the triquadratic one) and the basis is scikit-fem's ElementHexS2.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from skfem import Basis

from .checks import jacobians
from .elements import ElementKind, skfem_corner_subsets, skfem_vertex_order
from .raw import MeshFileError, RawMesh, labels_text

INTORDER = {"tet": 4, "hex": 5}  # exact for the consistent mass of straight P2 tets / 27-node bricks


@dataclass
class ImportedMesh:
    basis: Basis
    nodes: np.ndarray          # (n, 3) SI, rotation axis = Z
    node_label: np.ndarray     # (n,) file label of each node
    element_label: np.ndarray  # (e,) file label of each element, in mesh order
    rotation: np.ndarray       # (3, 3): x_model = rotation @ (scale * x_file)
    kind: ElementKind

    def nodes_of_labels(self, labels) -> np.ndarray:
        """Model node indices of file node labels (labels of nodes that no element uses dropped)."""
        lookup = {int(lab): i for i, lab in enumerate(self.node_label)}
        return np.array(sorted({lookup[int(lab)] for lab in np.ravel(labels) if int(lab) in lookup}), dtype=int)


def axis_rotation(axis) -> np.ndarray:
    """Proper rotation R with R a = e_z (Rodrigues' formula about a x e_z)."""
    a = np.asarray(axis, float) / np.linalg.norm(axis)
    z = np.array([0.0, 0.0, 1.0])
    v, c = np.cross(a, z), float(a @ z)
    if np.linalg.norm(v) < 1e-14:
        return np.eye(3) if c > 0 else np.diag([1.0, -1.0, -1.0])
    vx = np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])
    return np.eye(3) + vx + vx @ vx / (1.0 + c)


def _rows(raw: RawMesh) -> np.ndarray:
    """Coordinate rows of the connectivity's node labels (raise naming unknown labels)."""
    conn = raw.connectivity
    known = np.isin(conn, raw.node_labels)
    if not known.all():
        bad = np.flatnonzero(~known.all(axis=1))
        raise MeshFileError(f"{raw.path}: elements {labels_text(raw.element_labels[bad])} use node labels "
                            f"{labels_text(np.unique(conn[~known]))} that no *NODE / $Nodes block defines")
    return raw.node_index(conn.ravel()).reshape(conn.shape)


def _serendipity_points(x: np.ndarray, kind: ElementKind) -> tuple[np.ndarray, list]:
    """The face centres and the centre of 20-node bricks x (e, 20, 3), and their corner subsets."""
    names = [frozenset(c) for c in kind.nodes]
    corner = {c: names.index(frozenset([c])) for c in range(8)}
    edge = {names[j]: j for j in range(8, 20)}
    points, subsets = [], []
    for face in kind.faces:
        mids = [edge[frozenset(p)] for p in zip(face, face[1:] + face[:1])]
        points.append(0.5 * x[:, mids].sum(1) - 0.25 * x[:, [corner[c] for c in face]].sum(1))
        subsets.append(tuple(face))
    points.append(0.25 * x[:, 8:20].sum(1) - 0.25 * x[:, :8].sum(1))
    subsets.append(tuple(range(8)))
    return np.stack(points, axis=1), subsets


def build_mesh(raw: RawMesh, kind: ElementKind, scale: float, axis, intorder: int | None = None) -> ImportedMesh:
    """Mesh and basis of the file's elements; coordinates scaled to metres and rotated axis -> Z;
    ``intorder`` (the exact-mass rule of :data:`INTORDER` by default) sets the quadrature."""
    R = axis_rotation(axis)
    rows = _rows(raw)
    points = raw.coordinates @ R.T * scale
    element, mesh_cls = kind.skfem()
    node_names = list(kind.nodes)
    inverse = np.argsort(skfem_vertex_order(kind))       # file corner -> scikit-fem vertex
    if kind.n_nodes == 20:                                # synthetic face and centre points
        extra, subsets = _serendipity_points(points[rows], kind)
        start = len(points)
        points = np.vstack([points, extra.reshape(-1, 3)])
        rows = np.hstack([rows, start + np.arange(extra.shape[0] * extra.shape[1]).reshape(extra.shape[:2])])
        node_names += subsets
    names = [frozenset(int(inverse[c]) for c in n) for n in node_names]
    mesh_names = skfem_corner_subsets(mesh_cls.elem()) if not kind.linear else \
        [frozenset([i]) for i in range(kind.n_corners)]
    t = rows[:, [names.index(n) for n in mesh_names]]
    mesh = mesh_cls(points.T.copy(), t.T.copy())
    intorder = INTORDER[kind.shape] if intorder is None else intorder
    jacobians(mesh, raw.element_labels, intorder, raw.path)
    basis = Basis(mesh, element, intorder=intorder)
    local = [names.index(n) for n in skfem_corner_subsets(element)]
    file_row = np.full(basis.N, -1)
    file_row[basis.element_dofs] = rows[:, local].T
    labels = np.append(raw.node_labels, -np.ones(len(points) - len(raw.node_labels), np.int64))
    return ImportedMesh(basis=basis, nodes=basis.doflocs.T.copy(), node_label=labels[file_row],
                        element_label=raw.element_labels.copy(), rotation=R, kind=kind)
