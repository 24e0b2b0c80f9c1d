"""Contact pairs: where the friction elements sit and which displacements they read.

A pair i reads one displacement of each body, u_ring(i) = Σ_a W^r_ia u_a and u_blisk(i) = Σ_a W^b_ia u_a
(``ring_weights``, ``blisk_weights``: sparse, rows over the model's nodes), and its relative
displacement d_i = F_i (u_ring(i) − u_blisk(i)) in its frame F_i (rows n, t1, t2). Its force λ_i acts
back through the transposes (virtual work). Two placements:

* ``nodes``: one pair per node of the ring's upper surface, the coincident groove node opposite (W are
  rows of the identity); the area is the node's consistent tributary area ∫ N_a dA. Nodes on the right
  cyclic cut are dropped and their area added to their left partners. The pair count follows the mesh.
* ``grid``: the upper surface is cut into n_theta × n_axial cells of equal extent in (θ, z), independent of
  the mesh. A cell's pair reads the cell averages of both bodies' displacements,

      W^r_ia = (1 / A^r_i) ∫_{cell i, ring} N_a dA,      W^b_ia = (1 / A^b_i) ∫_{cell i, groove} N_a dA,

  each side integrated by its own composite facet rule (a quadrature point belongs to the cell its
  (θ, z) falls in), and its area is the ring side's A_i = A^r_i > 0. Because the cells partition each
  surface, a uniform pressure p (λ_i = p A_i n_i) loads the ring with exactly its consistent load
  p ∫ N_a n dA, and the blisk too where both sides' cell areas agree. They agree exactly where every
  cell boundary falls on the edges of the rule's sub-squares (cells aligned with the facets, on
  meshes that need not coincide: the contact patch test); a boundary inside a sub-square is
  integrated to the sub-square's width (1/8 of a facet or finer), which is the grid's quadrature error.
  Weights may touch nodes of the right cyclic cut; the reduction folds them onto the left partners
  with each harmonic's inter-sector phase.
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
from skfem import FacetBasis

#: Sub-squares per direction of the composite facet rule tried, fewest first, until every grid cell holds
#: quadrature points of both sides (3 Gauss points per direction in each)
SUBDIVISIONS = (8, 16, 32)


def composite_rule(n_sub: int) -> tuple[np.ndarray, np.ndarray]:
    """Points (2, k) and weights (k,) on the unit square: n_sub × n_sub sub-squares, 3 × 3 Gauss each.
    Exact for the facet's polynomials of degree ≤ 5 per direction; a cell boundary on a sub-square's
    edge is integrated exactly, any other to the sub-square's width."""
    g, w = np.polynomial.legendre.leggauss(3)
    x1 = ((np.arange(n_sub)[:, None] + 0.5 * (g + 1)) / n_sub).ravel()
    w1 = np.tile(0.5 * w / n_sub, n_sub)
    return np.stack(np.meshgrid(x1, x1, indexing="ij")).reshape(2, -1), np.outer(w1, w1).ravel()


@dataclass
class ContactPairs:
    """The pairs of a sector model (module docstring)."""

    ring_weights: sp.csr_matrix   # (m, n_nodes)
    blisk_weights: sp.csr_matrix  # (m, n_nodes)
    frame: np.ndarray             # (m, 3, 3) rows n, t1, t2 (Cartesian components)
    position: np.ndarray          # (m, 3) at rest
    tributary_area: Callable[[], np.ndarray] = field(repr=False)  # computes ``area``

    def __len__(self) -> int:
        return self.ring_weights.shape[0]

    @functools.cached_property
    def area(self) -> np.ndarray:
        """(m,) pair area (m^2), positive. Computed on first use (a facet quadrature for ``nodes``; the
        reduction stage never needs it)."""
        return self.tributary_area()

    @property
    def ring_node(self) -> np.ndarray:
        """(m,) the ring node of largest weight of each pair (for ``nodes``: the pair's node)."""
        return np.asarray(abs(self.ring_weights).argmax(axis=1)).ravel()

    @property
    def blisk_node(self) -> np.ndarray:
        """(m,) the blisk node of largest weight of each pair."""
        return np.asarray(abs(self.blisk_weights).argmax(axis=1)).ravel()

    @property
    def nodes(self) -> np.ndarray:
        """Every node some pair reads, sorted."""
        return np.unique(np.concatenate([self.ring_weights.indices, self.blisk_weights.indices]))

    def pair_of_node(self, n_nodes: int) -> np.ndarray:
        """(n_nodes,) for each node the pair that weighs it most on either side, −1 where none does
        (a point field for ParaView)."""
        out = np.full(n_nodes, -1)
        for W in (self.ring_weights, self.blisk_weights):
            Wc = abs(W).tocsc()
            read = np.flatnonzero(np.diff(Wc.indptr))
            out[read] = np.asarray(Wc[:, read].argmax(axis=0)).ravel()
        return out


def node_pairs(ring_nodes, blisk_nodes, n_nodes: int, frame, position, tributary_area) -> ContactPairs:
    """Pairs of coincident nodes: ring node ``ring_nodes[i]`` against ``blisk_nodes[i]``."""
    m = len(ring_nodes)

    def identity_rows(cols):
        return sp.csr_matrix((np.ones(m), (np.arange(m), np.asarray(cols))), shape=(m, n_nodes))

    return ContactPairs(ring_weights=identity_rows(ring_nodes), blisk_weights=identity_rows(blisk_nodes),
                        frame=frame, position=position, tributary_area=tributary_area)


@dataclass
class CellWeights:
    """One side's cell integrals: ``W`` (cells × nodes) = ∫_cell N_a dA, ``area`` and ``moment``
    (∫_cell x dA) per cell."""

    W: sp.csr_matrix
    area: np.ndarray
    moment: np.ndarray


def cell_weights(mesh, element, facets, rule, cell_of: Callable[[np.ndarray], np.ndarray], n_cells: int,
                 n_nodes: int) -> CellWeights:
    """∫_cell N_a dA over ``facets`` with the composite ``rule`` (a scalar element: its DoFs are the
    nodes), a quadrature point counting for the cell ``cell_of(x)`` gives it (x: (3, k) points; −1: in
    no cell)."""
    mapping = mesh.mapping()
    # skfem inverts the element map at the facet points by Newton to 1e-12 in reference units: on the
    # curved 27-node elements round-off can stall it just above that, 1e-10 is still far below the rule
    mapping.invF = functools.partial(mapping.invF, newton_tol=1e-10)
    fb = FacetBasis(mesh, element, mapping=mapping, facets=facets, quadrature=rule)
    x = fb.global_coordinates().value.reshape(3, -1)
    cell = cell_of(x)
    inside = cell >= 0
    dx = fb.dx.ravel()
    rows, cols, vals = [], [], []
    for j in range(fb.Nbfun):
        rows.append(cell[inside])
        cols.append(np.repeat(fb.element_dofs[j], fb.dx.shape[1])[inside])
        vals.append((fb.basis[j][0].value.ravel() * dx)[inside])
    W = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                      shape=(n_cells, n_nodes))
    cell, dx, x = cell[inside], dx[inside], x[:, inside]
    area = np.bincount(cell, weights=dx, minlength=n_cells)
    # the element's nodes off the facet: shape functions zero but for the inverse map's round-off
    W.data[np.abs(W.data) < 1e-12 * np.repeat(area, np.diff(W.indptr))] = 0.0
    W.eliminate_zeros()
    moment = np.stack([np.bincount(cell, weights=x[k] * dx, minlength=n_cells) for k in range(3)], axis=1)
    return CellWeights(W=W, area=area, moment=moment)


def cell_pairs(mesh, element, ring_facets, groove_facets, cell_of, n_cells: int, n_nodes: int,
               frames: Callable[[np.ndarray], np.ndarray], what: str) -> ContactPairs:
    """Cell-averaged pairs (module docstring, ``grid``) of the ring facets against the groove facets;
    ``frames(position)`` gives each pair's frame; ``what`` names the setting in errors. The composite
    facet rule is refined until every cell holds points of both sides."""
    for n_sub in SUBDIVISIONS:
        rule = composite_rule(n_sub)
        ring, groove = (cell_weights(mesh, element, f, rule, cell_of, n_cells, n_nodes)
                        for f in (ring_facets, groove_facets))
        if np.all(ring.area > 0) and np.all(groove.area > 0):
            break
    else:
        empty = np.flatnonzero((ring.area <= 0) | (groove.area <= 0))
        raise ValueError(f"{what}: {len(empty)} of {n_cells} contact cells cover no part of the ring's "
                         f"upper surface or of the groove (cells {empty[:10].tolist()}); use fewer cells")
    position = ring.moment / ring.area[:, None]
    area = ring.area
    return ContactPairs(ring_weights=sp.diags(1.0 / ring.area) @ ring.W,
                        blisk_weights=sp.diags(1.0 / groove.area) @ groove.W,
                        frame=frames(position), position=position, tributary_area=lambda: area)


def grid_cell_index(theta_range, z_range, n_theta: int, n_axial: int) -> Callable[[np.ndarray], np.ndarray]:
    """x (3, k) → the cell of the n_theta × n_axial grid of equal steps in θ = atan2(y, x) and z over
    the given ranges, θ-major (cell = i_theta · n_axial + i_z); −1 outside."""
    (t0, t1), (z0, z1) = theta_range, z_range

    def cell_of(x):
        s = (np.arctan2(x[1], x[0]) - t0) / (t1 - t0)
        t = (x[2] - z0) / (z1 - z0)
        inside = (s >= 0) & (s <= 1) & (t >= 0) & (t <= 1)
        i = np.minimum((s * n_theta).astype(int), n_theta - 1)
        k = np.minimum((t * n_axial).astype(int), n_axial - 1)
        return np.where(inside, i * n_axial + k, -1)

    return cell_of
