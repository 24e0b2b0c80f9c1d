"""The sector split into a fixed part, the same for every ring, and a morph zone that follows kappa.

The ring shape kappa moves only radial coordinates (``geometry.shape``, ``geometry.sector``): the
whole ring (its upper surface by delta1 b(theta), its lower surface by the delta2 and delta3 bumps)
and, of the blisk, the rim arm's nodes inside the ring's axial band, whose groove follows the ring's
upper surface with an offset delta1 b(theta) (r_arm - r) / (r_arm - R_c) that fades to zero at the
arm's outer surface. delta1 = kappa_to_offset(kappa1) is piecewise linear in kappa1 and every moved
coordinate is linear in delta1, so a blisk node moves for some kappa exactly when it sits elsewhere
at kappa1 = -1 or +1 than at kappa1 = 0.

* morph zone: the ring's elements and every blisk element with a node that moves;
* fixed part: every other element of the blisk. None of its nodes moves, so its element matrices,
  and anything built from them once (its prestress, a Craig-Bampton reduction per nodal diameter),
  are those of every ring;
* interface: the nodes the fixed part shares with the morph zone (none of them moves either).

Node indices are those of the FE model (``fem.model``: the nodes of the element order's basis).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from skfem import ElementHex1, ElementHex2
from skfem.assembly import Dofs

from .sector import BODY_RING, SectorMesh, build_sector

ELEMENTS = {1: ElementHex1, 2: ElementHex2}
#: kappa1 values whose meshes are compared with kappa1 = 0: the ends of the range
KAPPA1_ENDS = (-1.0, 1.0)


@dataclass
class SectorSplit:
    fixed_elements: np.ndarray   # element indices of the fixed part (blisk, kappa-independent)
    morph_elements: np.ndarray   # the ring and the blisk elements with a moving node
    moving_nodes: np.ndarray     # blisk nodes whose position depends on kappa1
    interface_nodes: np.ndarray  # nodes of both a fixed and a morph-zone element


def element_nodes(sector: SectorMesh, element_order: int) -> tuple[np.ndarray, np.ndarray]:
    """(node positions (n, 3), element-to-node map (n_local, n_elements)) of the FE model's nodes."""
    dofs = Dofs(sector.mesh, ELEMENTS[element_order]())
    positions = sector.mesh.doflocs if element_order == 2 else sector.mesh.p
    return positions.T, dofs.element_dofs


def split_sector(config: dict) -> SectorSplit:
    """The split of the sector of ``config`` (geometry and mesh sections) for every kappa."""
    order = config["mesh"]["element_order"]
    sectors = [build_sector(config, (k1, 0.0, 0.0)) for k1 in (0.0, *KAPPA1_ENDS)]
    positions = [element_nodes(s, order)[0] for s in sectors]
    elements = element_nodes(sectors[0], order)[1]
    moving = np.zeros(len(positions[0]), dtype=bool)
    for other in positions[1:]:
        moving |= np.any(other != positions[0], axis=1)
    ring = sectors[0].body == BODY_RING
    moving_blisk = np.unique(elements[:, ~ring][moving[elements[:, ~ring]]])
    morph = ring | np.any(moving[elements], axis=0)
    fixed_nodes = np.unique(elements[:, ~morph])
    morph_nodes = np.unique(elements[:, morph])
    return SectorSplit(fixed_elements=np.flatnonzero(~morph), morph_elements=np.flatnonzero(morph),
                       moving_nodes=moving_blisk,
                       interface_nodes=np.intersect1d(fixed_nodes, morph_nodes))
