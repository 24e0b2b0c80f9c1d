"""Cell-averaged contact pairs (ringdamper.fem.contact_pairs, placement ``grid``).

* Patch test: two 27-node blocks whose meshes do not coincide on the interface, pressed together by a
  uniform pressure through stiff stuck pairs on a grid that matches neither mesh. The exact solution
  (uniaxial stress in each block, a uniform normal jump p / k at the interface) solves the discrete
  equations to round-off; the pair areas sum to the interface area and a uniform pressure loads
  each block with its consistent load.
* On the sector: the areas sum to the ring's upper surface, and the reduced model with grid pairs
  (weights on the right cyclic face folded with the harmonic's phase) has the stuck frequencies of the
  full cyclic FE model.
"""
import copy

import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from skfem import Basis, ElementHex2, FacetBasis, LinearForm, MeshHex, asm

from ringdamper.config import ConfigError, validate_config
from ringdamper.fem.contact_law import stuck_pair_stiffness
from ringdamper.fem.contact_pairs import cell_pairs
from ringdamper.fem.elasticity import tangent_stiffness
from ringdamper.fem.model import _facets_within, build_model, contact_stiffness, relative_displacement_operator
from ringdamper.geometry.sector import build_sector
from ringdamper.modal.analysis import cyclic_modes
from ringdamper.reduction import modal_basis, modal_stuck_frequencies, reduce_sector, stuck_frequencies
from ringdamper.reduction.stage import reduction_sizes

E, NU, P, K_AREA = 2.0e11, 0.3, 1.0e6, 1.0e15   # Pa, -, Pa, N/m^3
BLOCKS = ((3, 3), (5, 3))                        # elements along x, y of the ring and the blisk block
N_CELLS = (2, 2)       # pairs along x, y: the cell lines x, y = 0.5 cut elements of both blocks in half


def _block(nx, ny, z0):
    mesh = MeshHex.init_tensor(np.linspace(0, 1, nx + 1), np.linspace(0, 1, ny + 1), np.linspace(z0, z0 + 1, 3))
    return mesh, Basis(mesh, ElementHex2(), intorder=5)


def _cells(n_cells):
    def cell_of(x):
        i = np.minimum((x[0] * n_cells[0]).astype(int), n_cells[0] - 1)
        k = np.minimum((x[1] * n_cells[1]).astype(int), n_cells[1] - 1)
        return i * n_cells[1] + k
    return cell_of


def _patch(n_cells):
    """Ring block z in [0, 1], blisk block z in [1, 2] (``BLOCKS``), the pairs' n = +z (ring towards
    blisk), both bodies' nodes stacked ring first."""
    (m_r, b_r), (m_b, b_b) = (_block(*BLOCKS[0], 0.0), _block(*BLOCKS[1], 1.0))
    n_r, n_b = int(b_r.N), int(b_b.N)
    top = m_r.facets_satisfying(lambda x: x[2] > 1 - 1e-12)
    bottom = m_b.facets_satisfying(lambda x: x[2] < 1 + 1e-12)
    cell_of, n_cells = _cells(n_cells), n_cells[0] * n_cells[1]
    frame = np.array([[0.0, 0, 1], [1, 0, 0], [0, 1, 0]])
    ring = cell_pairs(m_r, b_r.elem, top, top, cell_of, n_cells, n_r, lambda p: np.tile(frame, (len(p), 1, 1)), "t")
    blisk = cell_pairs(m_b, b_b.elem, bottom, bottom, cell_of, n_cells, n_b, lambda p: p, "t")
    W_r = sp.hstack([ring.ring_weights, sp.csr_matrix((n_cells, n_b))])
    W_b = sp.hstack([sp.csr_matrix((n_cells, n_r)), blisk.blisk_weights])
    F = ring.frame
    dW = (W_r - W_b).toarray()
    G = np.einsum("ikc,ia->ikac", F, dW).reshape(3 * n_cells, 3 * (n_r + n_b))
    consistent = [asm(LinearForm(lambda v, w: v), FacetBasis(m, b.elem, facets=f))
                  for m, b, f in ((m_r, b_r, top), (m_b, b_b, bottom))]
    return dict(meshes=(m_r, m_b), bases=(b_r, b_b), n=(n_r, n_b), area=ring.area, blisk_area=blisk.area,
                G=G, consistent=consistent)


@pytest.fixture(scope="module")
def patch():
    return _patch(N_CELLS)


def test_cells_inside_the_rule_sub_squares_err_by_less_than_their_width():
    """Three cells across three ring elements and five blisk elements: the lines x = 1/3, 2/3 fall
    inside sub-squares of the blisk's rule (width 1/40), so its cell areas carry that error."""
    cut = _patch((3, 1))
    assert cut["area"].sum() == pytest.approx(1.0, rel=1e-13)
    np.testing.assert_allclose(cut["area"], 1.0 / 3.0, rtol=1e-13)
    error = np.abs(cut["blisk_area"] - 1.0 / 3.0)
    assert cut["blisk_area"].sum() == pytest.approx(1.0, rel=1e-13)
    assert 0 < error.max() < 1.0 / 40.0


def test_areas_sum_to_the_interface_and_are_positive(patch):
    assert np.all(patch["area"] > 0)
    assert patch["area"].sum() == pytest.approx(1.0, rel=1e-13)
    np.testing.assert_allclose(patch["area"], 1.0 / (N_CELLS[0] * N_CELLS[1]), rtol=1e-13)
    np.testing.assert_allclose(patch["blisk_area"], patch["area"], rtol=1e-13)


def test_uniform_pressure_gives_each_side_its_consistent_load(patch):
    n_r, n_b = patch["n"]
    lam = np.zeros((len(patch["area"]), 3))
    lam[:, 0] = P * patch["area"]                      # normal force of each pair, N
    f = (patch["G"].T @ lam.ravel()).reshape(-1, 3)     # force on the nodes: G^T lambda
    ring_z, blisk_z = f[:n_r, 2], f[n_r:, 2]
    np.testing.assert_allclose(ring_z, P * patch["consistent"][0], atol=1e-9 * P)
    np.testing.assert_allclose(-blisk_z, P * patch["consistent"][1], atol=1e-9 * P)
    assert np.abs(f[:, :2]).max() < 1e-9 * P


def test_nonmatching_patch_transmits_a_uniform_pressure_exactly(patch):
    """Ring bottom on rollers (z = 0), blisk top loaded by -P e_z; the ring's rigid slides and spin held
    at two bottom corners, the blisk held by the pairs alone. Stuck springs k = K_AREA * A per pair,
    normal and tangential."""
    (_, m_b), (b_r, b_b), (n_r, n_b) = patch["meshes"], patch["bases"], patch["n"]
    K = sp.block_diag([tangent_stiffness(b, E, NU) for b in (b_r, b_b)]).tocsr()
    k = np.repeat(K_AREA * patch["area"], 3)
    K = K + sp.csr_matrix(patch["G"].T @ (k[:, None] * patch["G"]))
    top = m_b.facets_satisfying(lambda x: x[2] > 2 - 1e-12)
    load = asm(LinearForm(lambda v, w: v), FacetBasis(m_b, b_b.elem, facets=top))
    f = np.zeros(3 * (n_r + n_b))
    f[3 * n_r + 2::3] = -P * load
    x = np.vstack([b_r.doflocs.T, b_b.doflocs.T])
    bottom_nodes = np.flatnonzero(np.abs(x[:n_r, 2]) < 1e-12)
    origin, x_end = (bottom_nodes[np.linalg.norm(x[bottom_nodes, :2] - c, axis=1) < 1e-12][0] for c in ([0, 0], [1, 0]))
    fixed = [3 * a + 2 for a in bottom_nodes] + [3 * origin, 3 * origin + 1, 3 * x_end + 1]
    free = np.setdiff1d(np.arange(len(f)), fixed)
    u = np.zeros(len(f))
    u[free] = spla.spsolve(K[free][:, free].tocsc(), f[free])
    u = u.reshape(-1, 3)
    jump = P / K_AREA
    exact = np.column_stack([NU * P / E * x[:, 0], NU * P / E * x[:, 1], -P / E * x[:, 2]])
    exact[n_r:, 2] -= jump
    assert np.abs(u - exact).max() < 1e-9 * P / E


def test_sector_grid_areas_sum_to_the_upper_surface(small_config):
    cfg = copy.deepcopy(small_config)
    cfg["mesh"]["element_order"] = 2
    cfg["mesh"]["contact_pairs"] = {"placement": "grid", "n_theta": 7, "n_axial": 3}
    geometry = build_sector(cfg, (0.3, -0.5, 0.7))
    model = build_model(geometry, cfg)
    assert len(model.pairs) == 21 and np.all(model.pairs.area > 0)
    top = _facets_within(geometry.mesh, geometry.sets["ring_top"])
    surface = asm(LinearForm(lambda v, w: v), FacetBasis(geometry.mesh, model.basis.elem, facets=top)).sum()
    assert model.pairs.area.sum() == pytest.approx(surface, rel=1e-12)
    # a rigid translation of the ring opens nothing along the normal of a pair: d = F e
    G = relative_displacement_operator(model)
    u = np.zeros(model.n_dofs)
    ring = np.flatnonzero(model.node_body == model.node_body[model.pairs.ring_node[0]])
    u[3 * ring + 2] = 1.0
    np.testing.assert_allclose((G @ u).reshape(-1, 3), model.pairs.frame[:, :, 2], atol=1e-12)


@pytest.mark.parametrize("h", [0, 1])
def test_reduced_grid_pairs_match_the_full_cyclic_model(small_config, campaign_config, h):
    cfg = copy.deepcopy(small_config)
    cfg["mesh"]["element_order"] = 2
    cfg["mesh"]["contact_pairs"] = {"placement": "grid", "n_theta": 5, "n_axial": 2}
    model = build_model(build_sector(cfg, (0.3, -0.5, 0.7)), cfg)
    assert model.pairs.ring_weights[:, model.right_nodes].nnz > 0      # the fold is exercised
    kn, kt = stuck_pair_stiffness(model.pairs.area, cfg["contact"])
    rh = reduce_sector(model, 27, harmonics=[h], **reduction_sizes(campaign_config)).harmonics[0]
    full = cyclic_modes(model, model.K + contact_stiffness(model, kn, kt), model.M, rh.nd, 8, sigma=rh.sigma).frequency
    reduced = stuck_frequencies(rh, kn, kt, 8)
    flexible = np.abs(full) > 1.0
    assert np.max(np.abs(reduced[flexible] - full[flexible]) / full[flexible]) < 1e-3
    # what reduced.nc carries (the modes at the contact rows B_h) gives the same stuck model
    mb = modal_basis(rh, 0)
    np.testing.assert_allclose(modal_stuck_frequencies(mb.omega2, mb.contact, kn, kt, 8), reduced, rtol=1e-8)


@pytest.mark.parametrize("pairs, field", [({"placement": "grid", "n_theta": 4}, "mesh.contact_pairs"),
                                          ({"placement": "nodes", "n_axial": 2}, "mesh.contact_pairs.n_axial")])
def test_contact_pairs_config_errors_name_the_field(campaign_config, pairs, field):
    cfg = copy.deepcopy(campaign_config)
    cfg["mesh"]["contact_pairs"] = pairs
    with pytest.raises(ConfigError, match=field.replace(".", r"\.")):
        validate_config(cfg)
