"""Which DoFs of the sector the reduction keeps, and in what role (paper §2.5.1; docs/design.md §3.3).

The retained (Craig–Bampton boundary) DoFs are

* ``physical``: every DoF of the nodes the contact pairs read (a node of the right cyclic face
  replaced by its left partner) and of the blade-tip forcing/response node. They stay physical
  coordinates through every step, so the contact law and the forcing act on them directly
  (``contact``, ``response`` name the two subsets);
* ``left``: the free DoFs of the left cyclic face that are not ``physical`` (a few contact nodes lie
  on the left cut: they are physical, not interface). Mead's constraint keeps them, and the interface
  reduction replaces them by a static lift from the physical DoFs plus ``n_if`` interface modes;
* ``right``: the free DoFs of the right cyclic face, eliminated by Mead's constraint.

``right_of_left`` gives, for every right-face DoF, the left-face DoFs it is expressed by through the
12° rotation (node-wise, so a right-face x DoF depends on the partner's x and y). Clamped (bore) DoFs
are removed from the start. All indices are global sector DoFs (3 a + c for node a, component c).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..fem.model import SectorModel, node_dofs


@dataclass
class Partition:
    n_dofs: int              # all DoFs of the sector (clamped included)
    free: np.ndarray         # unclamped DoFs
    contact: np.ndarray      # DoFs of the nodes the pairs read, right face folded (sorted)
    response: np.ndarray     # DoFs of the blade-tip node (x, y, z)
    physical: np.ndarray     # contact U response, sorted
    left: np.ndarray         # free left-face DoFs that are not physical, node-major
    right: np.ndarray        # free right-face DoFs, node-major
    left_nodes: np.ndarray   # free left-face nodes (partners of right_nodes)
    right_nodes: np.ndarray

    @property
    def boundary(self) -> np.ndarray:
        """Craig–Bampton retained DoFs, in the order [physical, left, right]."""
        return np.concatenate([self.physical, self.left, self.right])

    @property
    def interior(self) -> np.ndarray:
        return np.setdiff1d(self.free, self.boundary)


def contact_nodes(model: SectorModel) -> np.ndarray:
    """The nodes the contact pairs read, those of the right cyclic face replaced by their left partners
    (Mead's constraint expresses them by those)."""
    nodes = model.pairs.nodes
    right_to_left = np.full(len(model.nodes), -1)
    right_to_left[np.asarray(model.right_nodes)] = model.left_nodes
    on_right = right_to_left[nodes] >= 0
    return np.unique(np.concatenate([nodes[~on_right], right_to_left[nodes[on_right]]]))


def partition(model: SectorModel) -> Partition:
    fixed = np.zeros(model.n_dofs, dtype=bool)
    fixed[model.fixed_dofs] = True
    free = np.flatnonzero(~fixed)

    left_n, right_n = np.asarray(model.left_nodes), np.asarray(model.right_nodes)
    left_fixed = fixed[node_dofs(left_n)].reshape(-1, 3)
    right_fixed = fixed[node_dofs(right_n)].reshape(-1, 3)
    if not (np.all(left_fixed == left_fixed[:, :1]) and np.array_equal(left_fixed, right_fixed)):
        raise ValueError("a cyclic-face node is partly clamped or clamped on one side only")
    keep = ~left_fixed[:, 0]
    left_n, right_n = left_n[keep], right_n[keep]

    contact = node_dofs(contact_nodes(model))
    response = node_dofs([model.tip_node])
    physical = np.union1d(contact, response)
    if np.any(fixed[physical]):
        raise ValueError("a contact or response node is clamped")
    right = node_dofs(right_n)
    if np.intersect1d(right, physical).size:
        raise ValueError("the response node lies on the right cyclic face")
    left_all = node_dofs(left_n)
    left = left_all[~np.isin(left_all, physical)]
    return Partition(n_dofs=model.n_dofs, free=free, contact=contact, response=response,
                     physical=physical, left=left, right=right, left_nodes=left_n,
                     right_nodes=right_n)
