"""The FE model of one sector: nodes, DoF sets, contact pairs and the elastic matrices.

Nodes are the scalar degrees of freedom of the chosen brick (8-node or 27-node Lagrange, scikit-fem);
the vector DoFs of node i are 3i, 3i+1, 3i+2 (x, y, z). Linear elasticity, lumped nothing: K and M are
the consistent matrices of both bodies (blisk and ring are disconnected in K, coupled only through
the contact pairs).

Contact pairs (docs/design.md §2; :mod:`ringdamper.fem.contact_pairs`): ``mesh.contact_pairs.placement``
``nodes``, one per node of the ring's upper surface against the coincident groove node, or ``grid``,
cell-averaged pairs on an n_theta × n_axial grid of the upper surface, independent of the mesh. Local
frame per pair: n = outward normal of the ring's upper surface r = R_c + delta1 b(theta) (from the
ring towards the blisk), t1 circumferential in the tangent plane, t2 = e_z; the relative displacement
d = F (u_ring - u_blisk) with d_n > 0 closing the contact.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from scipy.spatial import cKDTree
from skfem import Basis, ElementHex1, ElementHex2, FacetBasis, LinearForm, asm

from ..config import contact_pairs_setting
from ..geometry.sector import BODY_RING, MERGE_TOL, SectorMesh
from ..geometry.shape import upper_slope
from .contact_law import spring_diagonal, stuck_pair_stiffness
from .contact_pairs import ContactPairs, cell_pairs, grid_cell_index, node_pairs
from .elasticity import mass_matrix, tangent_stiffness

INTORDER = {1: 3, 2: 5}  # Gauss rule exact for the mass matrix of each order (docs/design.md §9)
ELEMENTS = {1: ElementHex1, 2: ElementHex2}


class CyclicSectorDofs:
    """The DoF layout every cyclic sector model shares, built-in or imported: three displacements
    per node, interleaved (``3a, 3a+1, 3a+2``), over ``nodes``; the sector angle ``2π / n_sectors``;
    the clamped DoFs of ``fixed_nodes``."""

    nodes: np.ndarray
    n_sectors: int
    fixed_nodes: np.ndarray

    @property
    def n_dofs(self) -> int:
        return 3 * len(self.nodes)

    @property
    def sector_angle(self) -> float:
        return 2.0 * np.pi / self.n_sectors

    @property
    def fixed_dofs(self) -> np.ndarray:
        return node_dofs(self.fixed_nodes)


@dataclass
class SectorModel(CyclicSectorDofs):
    geometry: SectorMesh
    basis: Basis              # scalar basis (vector DoFs of node a: 3a, 3a+1, 3a+2)
    nodes: np.ndarray         # (n_nodes, 3) node coordinates
    node_body: np.ndarray     # (n_nodes,) BODY_*
    element_order: int
    material: dict
    n_sectors: int
    fixed_nodes: np.ndarray   # clamped at the bore
    left_nodes: np.ndarray    # matched: right = rotation(2 pi / N) of left, same body
    right_nodes: np.ndarray
    pairs: ContactPairs
    tip_node: int
    K: sp.csr_matrix
    M: sp.csr_matrix

    def response_dof(self) -> int:
        """Z DoF of the blade-tip forcing / response node."""
        return 3 * self.tip_node + 2

    def part_mass(self, parts) -> sp.csr_matrix:
        """Mass matrix of the elements of the given parts (for modal energy fractions)."""
        elements = np.flatnonzero(np.isin(self.geometry.part, parts))
        sub = Basis(self.geometry.mesh, self.basis.elem, elements=elements,
                    intorder=INTORDER[self.element_order])
        return mass_matrix(sub, self.material["density"])


def node_dofs(nodes) -> np.ndarray:
    """Vector DoFs (x, y, z interleaved) of the given nodes."""
    nodes = np.asarray(nodes)
    return (3 * nodes[:, None] + np.arange(3)).ravel()


def _facets_within(mesh, vertices) -> np.ndarray:
    return np.flatnonzero(np.all(np.isin(mesh.facets, vertices), axis=0))


def _match(a_points, b_points, what: str) -> np.ndarray:
    """Index into b of the point coinciding with each a point (raise if any is missing)."""
    dist, idx = cKDTree(b_points).query(a_points)
    if len(a_points) and dist.max() > MERGE_TOL:
        raise RuntimeError(f"{what}: {np.sum(dist > MERGE_TOL)} nodes have no partner "
                           f"(max distance {dist.max():.3g} m)")
    return idx


def _rotation_z(angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _cyclic_nodes(nodes, node_body, half_angle):
    ang = np.arctan2(nodes[:, 1], nodes[:, 0])
    left = np.flatnonzero(np.abs(ang + half_angle) < 1e-9)
    right = np.flatnonzero(np.abs(ang - half_angle) < 1e-9)
    if len(left) != len(right):
        raise RuntimeError(f"cyclic faces differ: {len(left)} left vs {len(right)} right nodes")
    rotated = nodes[left] @ _rotation_z(2 * half_angle).T
    partner = np.empty(len(left), dtype=int)
    for body in np.unique(node_body[left]):
        lb = node_body[left] == body
        rb = right[node_body[right] == body]
        partner[lb] = rb[_match(rotated[lb], nodes[rb], "cyclic faces")]
    return left, partner


def _contact_frames(positions, geometry: SectorMesh) -> np.ndarray:
    """Rows n, t1, t2 of each pair's frame from the analytic upper surface r = R_c + d1 b(theta)."""
    theta = np.arctan2(positions[:, 1], positions[:, 0])
    r = np.hypot(positions[:, 0], positions[:, 1])
    a = upper_slope(theta, geometry.half_angle, geometry.deltas[0]) / r
    e_r = np.column_stack([np.cos(theta), np.sin(theta), np.zeros_like(theta)])
    e_t = np.column_stack([-np.sin(theta), np.cos(theta), np.zeros_like(theta)])
    e_z = np.tile([0.0, 0.0, 1.0], (len(theta), 1))
    norm = np.sqrt(1.0 + a**2)[:, None]
    n = (e_r - a[:, None] * e_t) / norm
    t1 = (e_t + a[:, None] * e_r) / norm
    return np.stack([n, t1, e_z], axis=1)


def _node_pairs(geometry, scalar_basis, nodes, node_body, left, right) -> ContactPairs:
    mesh = geometry.mesh
    top_facets = _facets_within(mesh, geometry.sets["ring_top"])
    groove_facets = _facets_within(mesh, geometry.sets["groove"])
    ring_nodes = np.unique(scalar_basis.get_dofs(top_facets).all())
    groove_nodes = np.unique(scalar_basis.get_dofs(groove_facets).all())
    # fold the right cut onto the left cut: one pair per physical node pair
    right_to_left = dict(zip(right, left))
    keep = np.array([n not in right_to_left for n in ring_nodes])
    folded, ring_nodes = ring_nodes[~keep], ring_nodes[keep]

    def tributary_area() -> np.ndarray:
        area_field = asm(LinearForm(lambda v, w: v), FacetBasis(mesh, scalar_basis.elem, facets=top_facets))
        area = area_field.copy()
        for node in folded:
            area[right_to_left[node]] += area_field[node]
        return area[ring_nodes]

    blisk_nodes = groove_nodes[_match(nodes[ring_nodes], nodes[groove_nodes], "contact pairs")]
    assert np.all(node_body[ring_nodes] == BODY_RING) and np.all(node_body[blisk_nodes] != BODY_RING)
    positions = nodes[ring_nodes]
    return node_pairs(ring_nodes, blisk_nodes, len(nodes), _contact_frames(positions, geometry), positions,
                      tributary_area)


def _grid_pairs(geometry, scalar_basis, nodes, n_theta: int, n_axial: int) -> ContactPairs:
    """Cell-averaged pairs on n_theta × n_axial cells of the upper surface over the whole sector angle
    and the ring's axial band."""
    mesh = geometry.mesh
    top_facets = _facets_within(mesh, geometry.sets["ring_top"])
    band = nodes[np.unique(scalar_basis.get_dofs(top_facets).all()), 2]
    cell_of = grid_cell_index((-geometry.half_angle, geometry.half_angle), (band.min(), band.max()),
                              n_theta, n_axial)
    return cell_pairs(mesh, scalar_basis.elem, top_facets, _facets_within(mesh, geometry.sets["groove"]),
                      cell_of, n_theta * n_axial, len(nodes), lambda p: _contact_frames(p, geometry),
                      "mesh.contact_pairs")


def _contact_pairs(geometry, scalar_basis, nodes, node_body, left, right, placement: dict) -> ContactPairs:
    if placement["placement"] == "grid":
        return _grid_pairs(geometry, scalar_basis, nodes, placement["n_theta"], placement["n_axial"])
    return _node_pairs(geometry, scalar_basis, nodes, node_body, left, right)


def build_model(geometry: SectorMesh, config: dict, elements: np.ndarray | None = None) -> SectorModel:
    """Assemble K, M and every DoF set of the sector model. With ``elements`` (element indices) the
    basis, K and M (and every quantity assembled on ``model.basis``) cover only those elements; the
    nodes, DoF numbering and DoF sets stay those of the whole sector."""
    order = config["mesh"]["element_order"]
    mat = config["material"]
    scalar = Basis(geometry.mesh, ELEMENTS[order](), intorder=INTORDER[order], elements=elements)
    nodes = scalar.doflocs.T.copy()
    node_body = np.zeros(len(nodes), dtype=int)
    node_body[np.unique(scalar.dofs.element_dofs[:, geometry.body == BODY_RING])] = BODY_RING
    fixed = np.unique(scalar.get_dofs(_facets_within(geometry.mesh, geometry.sets["bore"])).all())
    left, right = _cyclic_nodes(nodes, node_body, geometry.half_angle)
    pairs = _contact_pairs(geometry, scalar, nodes, node_body, left, right, contact_pairs_setting(config))
    tip = int(np.argmin(np.linalg.norm(nodes - geometry.vertices[geometry.tip_vertex], axis=1)))
    return SectorModel(
        geometry=geometry, basis=scalar, nodes=nodes, node_body=node_body, element_order=order,
        material=mat, n_sectors=config["geometry"]["n_sectors"], fixed_nodes=fixed,
        left_nodes=left, right_nodes=right, pairs=pairs, tip_node=tip,
        K=tangent_stiffness(scalar, mat["young_modulus"], mat["poisson_ratio"]),
        M=mass_matrix(scalar, mat["density"]))


def relative_displacement_operator(model: SectorModel) -> sp.csr_matrix:
    """G (3m x n_dofs): stacked [d_n, d_t1, d_t2] of every pair, d = F (u_ring - u_blisk) with
    u_ring, u_blisk the pair's weighted node displacements (:mod:`ringdamper.fem.contact_pairs`)."""
    pairs = model.pairs
    W = (pairs.ring_weights - pairs.blisk_weights).tocoo()
    F = pairs.frame[W.row]                                    # (nnz, 3 directions, 3 components)
    rows = 3 * W.row[:, None, None] + np.arange(3)[None, :, None]
    cols = 3 * W.col[:, None, None] + np.arange(3)[None, None, :]
    vals = F * W.data[:, None, None]
    G = sp.coo_matrix((vals.ravel(), (np.broadcast_to(rows, vals.shape).ravel(),
                                      np.broadcast_to(cols, vals.shape).ravel())),
                      shape=(3 * len(pairs), model.n_dofs))
    G = G.tocsr()
    G.eliminate_zeros()
    return G


def stuck_contact_stiffness(model: SectorModel, contact_cfg: dict, closed=True) -> sp.csr_matrix:
    """Linearised stuck contact (:func:`~ringdamper.fem.contact_law.stuck_pair_stiffness` on the
    ``closed`` pairs, all pairs by default)."""
    return contact_stiffness(model, *stuck_pair_stiffness(model.pairs.area, contact_cfg, closed))


def contact_stiffness(model: SectorModel, kn, kt) -> sp.csr_matrix:
    """Stuck linearised contact: G^T diag(kn, kt, kt) G (kn, kt per pair or scalar, N/m)."""
    k = spring_diagonal(kn, kt, len(model.pairs))
    G = relative_displacement_operator(model)
    return (G.T @ sp.diags(k.ravel()) @ G).tocsr()
