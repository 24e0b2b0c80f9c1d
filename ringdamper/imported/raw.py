"""What a mesh file holds, as the file says it: node labels and coordinates (file units), one element
type's connectivity in the file's node order and labels, and the named node and element sets."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np


class MeshFileError(ValueError):
    """A mesh file cannot be used; the message names the file, the set and the labels at fault."""


@dataclass
class RawMesh:
    path: Path
    node_labels: np.ndarray            # (n,) the file's own node labels
    coordinates: np.ndarray            # (n, 3) in the file's length unit
    blocks: dict                       # element type name -> (labels (e,), node labels (e, nodes), file order)
    node_sets: dict = field(default_factory=dict)      # name -> node labels
    element_sets: dict = field(default_factory=dict)   # name -> element labels
    surfaces: dict = field(default_factory=dict)       # name -> node labels of the faces (Abaqus *SURFACE)

    @property
    def element_type(self) -> str:
        """The one element type of the file (the checks reject several)."""
        return next(iter(self.blocks))

    @property
    def element_labels(self) -> np.ndarray:
        return self.blocks[self.element_type][0]

    @property
    def connectivity(self) -> np.ndarray:
        return self.blocks[self.element_type][1]

    def find_set(self, name: str) -> str | None:
        """The set called ``name`` (exactly, else ignoring case as Abaqus does), or None."""
        names = self.set_names()
        if name in names:
            return name
        hits = [n for n in names if n.upper() == name.upper()]
        return hits[0] if len(hits) == 1 else None

    def set_names(self) -> list[str]:
        return sorted(set(self.node_sets) | set(self.element_sets) | set(self.surfaces))

    def node_index(self, labels) -> np.ndarray:
        """Row of each node label in ``coordinates``."""
        order = np.argsort(self.node_labels)
        pos = np.searchsorted(self.node_labels, labels, sorter=order)
        return order[np.clip(pos, 0, len(order) - 1)]

    def nodes_of(self, name: str) -> np.ndarray:
        """Node labels of a node set, of a surface, or of the elements of an element set."""
        if name in self.node_sets:
            return np.unique(self.node_sets[name])
        if name in self.surfaces:
            return np.unique(self.surfaces[name])
        rows = np.isin(self.element_labels, self.element_sets[name])
        return np.unique(self.connectivity[rows])


def labels_text(labels, limit: int = 10) -> str:
    """'1, 2, 3 (and 7 more)'."""
    labels = list(np.asarray(labels).ravel())
    text = ", ".join(str(int(x)) for x in labels[:limit])
    return text + (f" (and {len(labels) - limit} more)" if len(labels) > limit else "")
