"""Each check on a small broken file: the error names the file, the set and the file's own labels."""
import numpy as np
import pytest

from ringdamper.imported.raw import MeshFileError
from ringdamper.imported.sector import load_imported_sector
from tests.imported.conftest import radius, write_deck

TITANIUM = {"young_modulus": 115e9, "poisson_ratio": 0.33, "density": 4430.0}


def load(imported):
    return load_imported_sector(imported, TITANIUM)


def fails(imported, *needles):
    with pytest.raises(MeshFileError) as err:
        load(imported)
    for needle in needles:
        assert needle in str(err.value), str(err.value)
    return str(err.value)


def broken(imported, raw, tmp_path, **kw):
    return {**imported, "mesh": str(write_deck(raw, tmp_path / "broken.inp", **kw))}


def test_the_example_passes_every_check(imported):
    sector = load(imported)
    assert sector.n_dofs == 3 * len(sector.nodes) and len(sector.left_nodes) == len(sector.right_nodes) > 0


def test_unknown_format(imported, tmp_path):
    (tmp_path / "sector.stl").write_text("solid x\n")
    fails({**imported, "mesh": str(tmp_path / "sector.stl")}, "sector.stl", "unknown mesh format '.stl'")


def test_a_deck_with_parts_is_refused_with_how_to_flatten(imported, tmp_path):
    (tmp_path / "parts.inp").write_text("*PART, NAME=BLISK\n*NODE\n1, 0., 0., 0.\n*END PART\n")
    fails({**imported, "mesh": str(tmp_path / "parts.inp")}, "parts.inp", "line 1", "*PART", "flat")


def test_mixed_element_types_are_counted(imported, example_raw, tmp_path):
    labels, conn = example_raw.blocks["C3D10"]
    example_raw.blocks["C3D4"] = (labels[:3] + 10**6, conn[:3, :4])
    fails(broken(imported, example_raw, tmp_path), "mixed solid element types", f"C3D10: {len(labels)}", "C3D4: 3")


def test_unsupported_element_type(imported, example_raw, tmp_path):
    fails(broken(imported, example_raw, tmp_path, element_type="C3D15"), "unsupported element type C3D15")


def test_linear_elements_only_on_request_with_the_locking_warning(imported, example_raw, tmp_path):
    labels, conn = example_raw.blocks.pop("C3D10")
    example_raw.blocks["C3D4"] = (labels, conn[:, :4])
    fails(broken(imported, example_raw, tmp_path), "linear element type C3D4", "lock in bending",
          "allow_linear_elements")


def test_a_missing_set_lists_the_sets_of_the_file(imported):
    fails({**imported, "sets": {**imported["sets"], "groove": "RIM_UNDERSIDE"}},
          "imported.sets.groove = 'RIM_UNDERSIDE': no such set", "BORE, CYC_HIGH, CYC_LOW")


def test_an_empty_set(imported, example_raw, tmp_path):
    example_raw.node_sets["BORE"] = np.array([10**7])   # a label no element uses
    fails(broken(imported, example_raw, tmp_path), "imported.sets.fixed = 'BORE' is empty")


def test_the_forcing_set_must_be_one_node(imported, example_raw):
    n = len(np.unique(example_raw.node_sets["GROOVE"]))
    fails({**imported, "sets": {**imported["sets"], "forcing": "GROOVE"}},
          "imported.sets.forcing = 'GROOVE' must hold exactly one node", f"it holds {n}")


def test_millimetre_coordinates_under_a_metre_unit(imported, example_raw, tmp_path):
    example_raw.coordinates *= 1000.0
    message = fails(broken(imported, example_raw, tmp_path), "look like millimetres", "length_unit: mm")
    assert "node " in message


def test_metre_coordinates_under_a_millimetre_unit(imported):
    fails({**imported, "length_unit": "mm"}, "look like metres", "length_unit: m")


def test_the_sector_angle_must_be_two_pi_over_n(imported):
    fails({**imported, "n_sectors": 20}, "CYC_LOW' -> 'CYC_HIGH' are 15 deg apart", "360/20 = 18 deg",
          "n_sectors = 24")


def test_unmatched_cyclic_nodes_are_listed_with_their_distance(imported, example_raw, tmp_path):
    high = example_raw.node_sets["CYC_HIGH"]
    moved = int(high[len(high) // 2])
    row = example_raw.node_index([moved])[0]
    example_raw.coordinates[row, 2] += 1e-4
    message = fails(broken(imported, example_raw, tmp_path), "1 nodes of 'CYC_LOW'", "have no 'CYC_HIGH' partner",
                    f"nearest 'CYC_HIGH' node {moved} is 0.0001 away")
    assert message.count("node ") >= 2


def test_an_inverted_element_is_named(imported, example_raw, tmp_path):
    labels, conn = example_raw.blocks["C3D10"]
    conn[7, [1, 2]] = conn[7, [2, 1]]          # corners 2 and 3 swapped: mirrored ...
    conn[7, [4, 6]] = conn[7, [6, 4]]          # ... with its mid-edge nodes, a valid but inverted tet
    conn[7, [8, 9]] = conn[7, [9, 8]]
    fails(broken(imported, example_raw, tmp_path), "1 elements have a non-positive Jacobian",
          f"elements {labels[7]} ")


def test_a_part_without_fixed_nodes_is_a_rigid_body_motion(imported, example_raw, tmp_path):
    labels, conn = example_raw.blocks["C3D10"]
    blade = np.isin(labels, example_raw.element_sets["BLADE"])
    shared = np.intersect1d(conn[blade], conn[~blade])          # the blade root's interface nodes
    copies = shared + 10**6
    rows = example_raw.node_index(shared)
    example_raw.node_labels = np.concatenate([example_raw.node_labels, copies])
    example_raw.coordinates = np.vstack([example_raw.coordinates, example_raw.coordinates[rows]])
    sub = conn[blade]
    conn[blade] = np.where(np.isin(sub, shared), sub + 10**6, sub)
    fails(broken(imported, example_raw, tmp_path), "imported.sets.fixed = 'BORE' leaves 1 of the sector's 2",
          "rigid-body motion", f"elements {labels[blade][0]}")


def test_a_groove_facing_away_from_the_axis(imported, example_raw, tmp_path):
    rim = example_raw.node_labels[np.isclose(radius(example_raw), 0.135, atol=1e-9, rtol=0)
                                  & (np.abs(example_raw.coordinates[:, 2]) < 0.0151)]
    example_raw.node_sets["RIM_TOP"] = rim
    fails(broken({**imported, "sets": {**imported["sets"], "groove": "RIM_TOP"}}, example_raw, tmp_path),
          "imported.sets.groove = 'RIM_TOP'", "face away from the axis", "faces of elements")
