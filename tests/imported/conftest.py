"""Fixtures of the import tests: the example blisk (coarse), its configuration section, and a writer of
edited decks (to break one thing at a time)."""
import copy

import numpy as np
import pytest

from ringdamper.imported.example import SETS, write_example
from ringdamper.imported.reader import read_mesh

COARSE = 0.02   # m: 518 tets, 3108 DoFs


@pytest.fixture(scope="session")
def example_files(tmp_path_factory):
    return write_example(tmp_path_factory.mktemp("example"), COARSE)


@pytest.fixture
def imported(example_files):
    """The ``imported`` configuration section of the example's .inp deck."""
    return {"mesh": str(example_files["inp"]), "length_unit": "m", "n_sectors": 24, "sets": dict(SETS)}


def write_deck(raw, path, element_type=None):
    """A RawMesh as a flat deck with its labels and sets (test helper)."""
    lines = ["*NODE"] + [f"{lab}, {x:.17g}, {y:.17g}, {z:.17g}"
                         for lab, (x, y, z) in zip(raw.node_labels, raw.coordinates)]
    for etype, (labels, conn) in raw.blocks.items():
        lines.append(f"*ELEMENT, TYPE={element_type or etype}")
        for lab, row in zip(labels, conn):
            values = [str(lab)] + [str(n) for n in row]
            rows = [values[:16], values[16:]] if len(values) > 16 else [values]
            lines += [", ".join(r) + ("," if k < len(rows) - 1 else "") for k, r in enumerate(rows)]
    for keyword, sets in (("NSET", raw.node_sets), ("ELSET", raw.element_sets)):
        for name, members in sets.items():
            lines.append(f"*{keyword}, {keyword}={name}")
            lines += [", ".join(str(m) for m in members[i:i + 16]) for i in range(0, len(members), 16)]
    path.write_text("\n".join(lines) + "\n")
    return path


@pytest.fixture
def example_raw(example_files):
    """A fresh RawMesh of the example deck, its solid block only."""
    raw = read_mesh(example_files["inp"])
    raw.blocks = {"C3D10": raw.blocks["C3D10"]}
    return copy.deepcopy(raw)


def radius(raw) -> np.ndarray:
    return np.hypot(raw.coordinates[:, 0], raw.coordinates[:, 1])
