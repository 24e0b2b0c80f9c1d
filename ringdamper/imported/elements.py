"""Node orderings of the supported solid elements and their scikit-fem counterparts.

Every local node of a file's element is named by the corner nodes it sits between: a corner by
itself, a mid-edge node by the edge's two corners, a mid-face node by the face's four corners, the
centre node of a 27-node brick by all eight. A scikit-fem local DoF is named the same way (the
corners nearest its reference location), so the two orderings are matched by these names and not by
position: a curved element is read exactly as the file writes it.

Abaqus orderings (Abaqus Analysis User's Guide, *Three-dimensional solid element library*): C3D10
mid-edge nodes 5-10 on edges 1-2, 2-3, 3-1, 1-4, 2-4, 3-4; C3D20 nodes 9-20 on edges 1-2, 2-3, 3-4,
4-1, 5-6, 6-7, 7-8, 8-5, 1-5, 2-6, 3-7, 4-8; C3D27 as C3D20, then the centre (node 21) and the
mid-face nodes 22-27 on faces 1234, 5678, 1265, 2376, 3487, 4158 (the order Gmsh's Abaqus export
writes). Gmsh (reference manual, *Node ordering*): corners as Abaqus;
tetrahedron10 edges 0-1, 1-2, 2-0, 3-0, 3-2, 3-1; hexahedron20/27 edges 0-1, 0-3, 0-4, 1-2, 1-5,
2-3, 2-6, 3-7, 4-5, 4-7, 5-6, 6-7, faces 0123, 0154, 0374, 1265, 2376, 4567, then the centre.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from skfem import (
    ElementHex1,
    ElementHex2,
    ElementHexS2,
    ElementTetP1,
    ElementTetP2,
    MeshHex1,
    MeshHex2,
    MeshTet1,
    MeshTet2,
)

_TET_EDGES = [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)]
_HEX_EDGES = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4), (0, 4), (1, 5), (2, 6), (3, 7)]
_HEX_CORNERS = [(i,) for i in range(8)]
_ABAQUS_HEX_FACES = [(0, 1, 2, 3), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
# the corners' reference coordinates (unit cube / unit tetrahedron) in the file's corner order
_HEX_REFERENCE = np.array([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)])
_TET_REFERENCE = np.array([(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)])


@dataclass(frozen=True)
class ElementKind:
    """One supported element: its file node order (corner subsets) and the scikit-fem element."""

    name: str
    nodes: tuple            # per local file node: the corners (file corner indices) it sits between
    shape: str              # "tet" or "hex"
    linear: bool
    faces: tuple            # corner tuples of the faces (Abaqus face numbering S1, S2, ...)

    @property
    def n_nodes(self) -> int:
        return len(self.nodes)

    @property
    def n_corners(self) -> int:
        return 4 if self.shape == "tet" else 8

    def skfem(self):
        """(scikit-fem element, mesh class) of this kind; 20-node bricks are read on a 27-node mesh
        whose extra nodes are the serendipity map's own face and centre points (exact geometry)."""
        if self.shape == "tet":
            return (ElementTetP1(), MeshTet1) if self.linear else (ElementTetP2(), MeshTet2)
        if self.linear:
            return ElementHex1(), MeshHex1
        return (ElementHex2(), MeshHex2) if self.n_nodes == 27 else (ElementHexS2(), MeshHex2)

    def corner_reference(self) -> np.ndarray:
        return _TET_REFERENCE if self.shape == "tet" else _HEX_REFERENCE


def _tet(name, quadratic):
    nodes = [(i,) for i in range(4)] + (_TET_EDGES if quadratic else [])
    faces = ((0, 1, 2), (0, 3, 1), (1, 3, 2), (2, 3, 0))
    return ElementKind(name, tuple(map(tuple, nodes)), "tet", not quadratic, faces)


def _hex(name, n):
    nodes = _HEX_CORNERS + (_HEX_EDGES if n > 8 else []) + ([tuple(range(8))] + _ABAQUS_HEX_FACES if n == 27 else [])
    return ElementKind(name, tuple(map(tuple, nodes)), "hex", n == 8, tuple(_ABAQUS_HEX_FACES))


ABAQUS = {
    "C3D10": _tet("C3D10", True), "C3D10R": _tet("C3D10R", True),
    "C3D20": _hex("C3D20", 20), "C3D20R": _hex("C3D20R", 20), "C3D27": _hex("C3D27", 27),
    "C3D4": _tet("C3D4", False), "C3D8": _hex("C3D8", 8), "C3D8R": _hex("C3D8R", 8),
}
_GMSH_HEX_EDGES = [(0, 1), (0, 3), (0, 4), (1, 2), (1, 5), (2, 3), (2, 6), (3, 7), (4, 5), (4, 7), (5, 6), (6, 7)]
_GMSH_HEX_FACES = [(0, 1, 2, 3), (0, 1, 4, 5), (0, 3, 4, 7), (1, 2, 5, 6), (2, 3, 6, 7), (4, 5, 6, 7)]
GMSH = {  # Gmsh element type number -> kind (Gmsh's own node order)
    4: _tet("tetrahedron4", False),
    11: ElementKind("tetrahedron10", tuple((i,) for i in range(4)) + ((0, 1), (1, 2), (0, 2), (0, 3), (2, 3), (1, 3)),
                    "tet", False, _tet("", True).faces),
    5: _hex("hexahedron8", 8),
    17: ElementKind("hexahedron20", tuple(_HEX_CORNERS + _GMSH_HEX_EDGES), "hex", False, tuple(_ABAQUS_HEX_FACES)),
    12: ElementKind("hexahedron27", tuple(_HEX_CORNERS + _GMSH_HEX_EDGES + _GMSH_HEX_FACES + [tuple(range(8))]),
                    "hex", False, tuple(_ABAQUS_HEX_FACES)),
}
KINDS = {**ABAQUS, **{k.name: k for k in GMSH.values()}}


def skfem_corner_subsets(element) -> list[frozenset]:
    """For each local DoF of a scalar scikit-fem element, the local vertices of the smallest entity
    holding its reference location: the tetrahedron's vertices with a positive barycentric
    coordinate there; the cube's vertices that agree with it on every axis where it is 0 or 1."""
    tet = element.refdom.nnodes == 4
    vertices = (ElementTetP1 if tet else ElementHex1).doflocs
    out = []
    for loc in element.doflocs:
        if tet:
            lam = np.linalg.solve(np.column_stack([np.ones(4), vertices]).T, np.array([1.0, *loc]))
            out.append(frozenset(np.flatnonzero(lam > 1e-12).tolist()))
        else:
            fixed = ~np.isclose(loc, 0.5)
            out.append(frozenset(np.flatnonzero(np.all(vertices[:, fixed] == loc[fixed], axis=1)).tolist()))
    return out


def skfem_vertex_order(kind: ElementKind) -> np.ndarray:
    """File corner index of each scikit-fem vertex (same reference coordinates, so the same map)."""
    vertices = (ElementTetP1 if kind.shape == "tet" else ElementHex1).doflocs
    ref = kind.corner_reference()
    return np.array([int(np.flatnonzero(np.all(ref == v, axis=1))[0]) for v in vertices])
