"""What meshio 5.3.5 (the pinned version) drops from the files a user brings; the reason the import
reads .inp and .msh itself (docs/imported.md)."""
import meshio
import numpy as np
import pytest

DECK = """*NODE, NSET=ALLN
101, 0., 0., 0.
102, 1., 0., 0.
103, 0., 1., 0.
104, 0., 0., 1.
*ELEMENT, TYPE=C3D4, ELSET=EALL
7, 101, 102, 103, 104
*NSET, NSET=GEN, GENERATE
101, 104, 2
*NSET, NSET=BYNAME
GEN, 104
*NSET, NSET=FROMEL, ELSET=EALL
*SURFACE, NAME=SURF, TYPE=ELEMENT
EALL, S1
"""


def test_meshio_drops_labels_set_references_and_surfaces(tmp_path):
    (tmp_path / "deck.inp").write_text(DECK)
    m = meshio.read(tmp_path / "deck.inp")
    assert m.cells[0].data.tolist() == [[0, 1, 2, 3]]             # node labels renumbered from 0
    assert not m.point_data and not m.cell_data                   # no labels kept anywhere
    assert m.point_sets["GEN"].tolist() == [0, 2]                 # GENERATE is read
    assert len(m.point_sets["BYNAME"]) == 0                       # a set named inside a set: dropped
    assert len(m.point_sets["FROMEL"]) == 0                       # *NSET, ELSET=: dropped
    assert "ALLN" not in m.point_sets                             # *NODE, NSET=: dropped
    assert "SURF" not in m.point_sets and "SURF" not in m.cell_sets   # *SURFACE: dropped


def test_meshio_reads_one_instance_of_a_part_in_part_coordinates(tmp_path):
    (tmp_path / "parts.inp").write_text(
        "*PART, NAME=P\n*NODE\n1, 0., 0., 0.\n2, 1., 0., 0.\n3, 0., 1., 0.\n4, 0., 0., 1.\n"
        "*ELEMENT, TYPE=C3D4\n1, 1, 2, 3, 4\n*END PART\n*ASSEMBLY, NAME=A\n*INSTANCE, NAME=I1, PART=P\n"
        "2., 0., 0.\n*END INSTANCE\n*INSTANCE, NAME=I2, PART=P\n*END INSTANCE\n*END ASSEMBLY\n")
    m = meshio.read(tmp_path / "parts.inp")
    assert len(m.cells[0].data) == 1 and np.allclose(m.points[:, 0].max(), 1.0)   # two instances -> one, untranslated


def test_meshio_refuses_a_deck_with_a_type_it_does_not_know(tmp_path):
    (tmp_path / "c3d27.inp").write_text("*NODE\n" + "".join(f"{i}, {i}., 0., 0.\n" for i in range(1, 28))
                                        + "*ELEMENT, TYPE=C3D27\n1, " + ", ".join(map(str, range(1, 17))) + ",\n"
                                        + ", ".join(map(str, range(17, 28))) + "\n")
    with pytest.raises(BaseException):
        meshio.read(tmp_path / "c3d27.inp")
