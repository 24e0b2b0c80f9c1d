"""The built-in blisk sector written as .inp and .msh and imported again: the same K and M to round-off;
a millimetre copy of a deck: the same frequencies to round-off."""
import numpy as np
import pytest
from skfem import Basis

from ringdamper.fem.elasticity import mass_matrix, tangent_stiffness
from ringdamper.fem.model import INTORDER, build_model
from ringdamper.geometry.sector import PART_RING, build_sector
from ringdamper.imported.elements import ABAQUS, GMSH
from ringdamper.imported.report import nd_frequencies
from ringdamper.imported.sector import load_imported_sector
from ringdamper.imported.writers import file_connectivity, write_inp, write_msh
from tests.imported.conftest import write_deck

SETS = {"fixed": "BORE", "cyclic_low": "CYC_LOW", "cyclic_high": "CYC_HIGH", "groove": "GROOVE",
        "forcing": "FORCING"}


@pytest.fixture(scope="module")
def builtin(campaign_config, tmp_path_factory):
    """The built-in sector's blisk (ring elements left out) as both formats, and its own K and M."""
    model = build_model(build_sector(campaign_config, (0.0, 0.0, 0.0)), campaign_config)
    blisk = np.flatnonzero(model.geometry.part != PART_RING)
    used = np.unique(model.basis.element_dofs[:, blisk])
    new = np.full(len(model.nodes), -1)
    new[used] = np.arange(len(used))
    sets = {name: new[np.intersect1d(nodes, used)] for name, nodes in (
        ("BORE", model.fixed_nodes), ("CYC_LOW", model.left_nodes), ("CYC_HIGH", model.right_nodes),
        ("GROOVE", model.pairs.blisk_node), ("FORCING", [model.tip_node]))}
    folder = tmp_path_factory.mktemp("builtin")
    write_inp(folder / "s.inp", model.nodes[used], new[file_connectivity(model.basis, ABAQUS["C3D27"])[blisk]],
              ABAQUS["C3D27"], sets, {})
    write_msh(folder / "s.msh", model.nodes[used], new[file_connectivity(model.basis, GMSH[12])[blisk]], 12, sets, {})
    sub = Basis(model.geometry.mesh, model.basis.elem, elements=blisk, intorder=INTORDER[2])
    mat = campaign_config["material"]
    dofs = (3 * used[:, None] + np.arange(3)).ravel()
    K = tangent_stiffness(sub, mat["young_modulus"], mat["poisson_ratio"])[dofs][:, dofs]
    M = mass_matrix(sub, mat["density"])[dofs][:, dofs]
    return folder, K, M, model


@pytest.mark.parametrize("suffix", [".inp", ".msh"])
def test_the_builtin_sector_round_trips_to_the_same_matrices(builtin, campaign_config, suffix):
    folder, K, M, model = builtin
    imported = {"mesh": str(folder / f"s{suffix}"), "length_unit": "m", "n_sectors": 30, "sets": SETS}
    sector = load_imported_sector(imported, campaign_config["material"])
    order = sector.mesh.node_label - 1                 # imported node i = written node label - 1
    dofs = (3 * order[:, None] + np.arange(3)).ravel()
    for ours, theirs in ((sector.K, K), (sector.M, M)):
        diff = abs(ours - theirs[dofs][:, dofs]).max()
        assert diff <= 1e-12 * abs(theirs).max()
    blisk_nodes = np.unique(model.basis.element_dofs[:, model.geometry.part != PART_RING])
    assert len(sector.left_nodes) == np.isin(model.left_nodes, blisk_nodes).sum()


def test_a_millimetre_copy_gives_the_same_frequencies(imported, example_raw, tmp_path, campaign_config):
    mat = campaign_config["material"]
    sector = load_imported_sector(imported, mat)
    metres = nd_frequencies(sector, [0.0, 2081.0], 2, nds=(0, 5, 12))
    example_raw.coordinates = example_raw.coordinates * 1000.0
    mm = {**imported, "mesh": str(write_deck(example_raw, tmp_path / "mm.inp")), "length_unit": "mm"}
    millimetres = nd_frequencies(load_imported_sector(mm, mat), [0.0, 2081.0], 2, nds=(0, 5, 12))
    f_m = np.array([r["frequency_hz"] for r in metres])
    f_mm = np.array([r["frequency_hz"] for r in millimetres])
    assert np.max(np.abs(f_mm / f_m - 1)) < 1e-10
