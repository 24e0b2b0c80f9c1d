"""Reduced model against the full FE cyclic model (docs/design.md §7 Craig–Bampton check).

At the campaign's settings (reduction section of config.yaml) the first 10 eigenfrequencies of ND 0, 3, 6, 9,
contact free and stuck, match ``modal.cyclic_modes`` of the full sector to 0.1 %: on the coarse quadratic mesh for
every ND, on the default campaign mesh for the target ND 3. Static condensation is exact (1e-8).
"""
import copy

import numpy as np
import pytest

from ringdamper.fem.contact_law import stuck_pair_stiffness
from ringdamper.fem.cyclic import cyclic_transform, project
from ringdamper.fem.linalg import solve
from ringdamper.fem.model import build_model, contact_stiffness
from ringdamper.geometry.sector import BODY_RING, build_sector
from ringdamper.modal.analysis import cyclic_modes
from ringdamper.reduction import eigenfrequencies, reduce_sector, stuck_frequencies, stuck_matrices
from ringdamper.reduction.craig_bampton import craig_bampton, interior_blocks
from ringdamper.reduction.partition import partition
from ringdamper.reduction.stage import reduction_sizes

EO = 27
FREQ_TOL = 1e-3          # 0.1 %
RIGID_HZ = 1.0           # reference modes below this are the ring's rigid motions (ND 0, contact free)
N_MODES = 10


def _compare(reduced, full):
    """Max relative error; reference rigid modes must be matched by rigid (< RIGID_HZ) modes."""
    rigid = np.abs(full) < RIGID_HZ
    assert np.all(np.abs(reduced[rigid]) < RIGID_HZ), (reduced, full)
    return float(np.max(np.abs(reduced[~rigid] - full[~rigid]) / full[~rigid]))


@pytest.fixture(scope="module")
def small_quadratic(small_config, campaign_config):
    cfg = copy.deepcopy(small_config)
    cfg["mesh"]["element_order"] = 2
    model = build_model(build_sector(cfg, (0.3, -0.5, 0.7)), cfg)
    # some pairs open (N0 <= 0): per-pair stiffness arrays with zeros
    N0 = np.where(np.arange(len(model.pairs)) % 4 == 1, -1.0, 10.0)
    kn, kt = stuck_pair_stiffness(model.pairs.area, cfg["contact"], N0 > 0)
    return model, kn, kt, reduce_sector(model, EO, n_harmonics=3, **reduction_sizes(campaign_config))


@pytest.mark.parametrize("h, nd", [(0, 0), (1, 3), (2, 6), (3, 9)])
def test_frequencies_match_full_model_small_mesh(small_quadratic, h, nd):
    model, kn, kt, rs = small_quadratic
    rh = rs.harmonics[h]
    assert rh.nd == nd
    Kc = contact_stiffness(model, kn, kt)
    full_free = cyclic_modes(model, model.K, model.M, nd, N_MODES, sigma=rh.sigma).frequency
    full_stuck = cyclic_modes(model, model.K + Kc, model.M, nd, N_MODES, sigma=rh.sigma).frequency
    assert _compare(eigenfrequencies(rh.K, rh.M, N_MODES), full_free) < FREQ_TOL
    assert _compare(stuck_frequencies(rh, kn, kt, N_MODES), full_stuck) < FREQ_TOL


@pytest.mark.slow
def test_target_nd_matches_full_model_default_mesh(config):
    model = build_model(build_sector(config, (1.0, -1.0, -1.0)), config)
    kn, kt = stuck_pair_stiffness(model.pairs.area, config["contact"])
    rs = reduce_sector(model, EO, harmonics=[1], **reduction_sizes(config))
    rh = rs.harmonics[0]
    assert rh.nd == 3
    Kc = contact_stiffness(model, kn, kt)
    full_free = cyclic_modes(model, model.K, model.M, 3, N_MODES, sigma=rh.sigma).frequency
    full_stuck = cyclic_modes(model, model.K + Kc, model.M, 3, N_MODES, sigma=rh.sigma).frequency
    assert _compare(eigenfrequencies(rh.K, rh.M, N_MODES), full_free) < FREQ_TOL
    assert _compare(stuck_frequencies(rh, kn, kt, N_MODES), full_stuck) < FREQ_TOL
    # DoF bookkeeping (paper: 6057 -> 1146 -> 783 -> 510): each step removes DoFs, and the final
    # model holds the physical contact/response DoFs, the interface modes and the fixed-interface modes
    counts = rs.dof_counts
    assert counts["full"] == model.n_dofs - len(model.fixed_dofs)
    assert counts["full"] > counts["craig_bampton"] > counts["mead"] > counts["interface"]
    assert counts["interface"] == rh.n_physical + rh.n_if + rh.n_fi
    assert counts["mead"] == rh.size_mead


def test_craig_bampton_static_condensation_is_exact(small_quadratic):
    """Real sector, stuck springs (ring held), no cyclic constraint: unit loads at every retained DoF."""
    model, kn, kt, _ = small_quadratic
    part = partition(model)
    cb = craig_bampton(model.K, model.M, part.boundary, part.interior, 12)
    Kc = contact_stiffness(model, kn, kt).tocsr()
    free, b = part.free, part.boundary
    K_full = (model.K + Kc).tocsr()[free][:, free]
    pos = np.searchsorted(free, b)
    loads = np.zeros((len(free), len(b)))
    loads[pos, np.arange(len(b))] = 1.0
    u_full = solve(K_full, loads)[pos]
    nb = len(b)
    K_red = cb.K[:nb, :nb] + Kc[b][:, b].toarray()
    u_red = np.linalg.solve(K_red, np.eye(nb))
    assert np.linalg.norm(u_red - u_full) / np.linalg.norm(u_full) < 1e-8


def test_constraint_modes_by_interior_blocks_match_the_dense_formulas(small_quadratic):
    """The interior splits into the ring and the blisk (no stiffness couples them without contact);
    Psi and K_cb, M_cb assembled block by block equal the dense formulas of the whole interior."""
    model, *_ = small_quadratic
    part = partition(model)
    cb = craig_bampton(model.K, model.M, part.boundary, part.interior, 12, keep_modes=True)
    K, M = model.K.tocsr(), model.M.tocsr()
    i, b = part.interior, part.boundary
    Kii, Kib, Mii, Mib = (A[i][:, j].toarray() for A in (K, M) for j in (i, b))
    psi = -np.linalg.solve(Kii, Kib)
    assert np.abs(cb.constraint_modes - psi).max() <= 1e-10 * np.abs(psi).max()
    nb = len(b)
    K_bb = K[b][:, b].toarray() + Kib.T @ psi
    M_bb = M[b][:, b].toarray() + Mib.T @ psi + psi.T @ Mib + psi.T @ Mii @ psi
    M_bf = (Mib.T + psi.T @ Mii) @ cb.fixed_interface_modes
    assert np.abs(cb.K[:nb, :nb] - K_bb).max() <= 1e-10 * np.abs(K_bb).max()
    # M_bb's reference sums four products of the dense-solve Psi: under OpenBLAS's Haswell kernel its
    # own rounding reaches 1.0e-10 of max |M_bb| (7.4e-12 of 0.073); a wrong block is off by O(1)
    assert np.abs(cb.M[:nb, :nb] - M_bb).max() <= 1e-9 * np.abs(M_bb).max()
    assert np.abs(cb.M[:nb, nb:] - M_bf).max() <= 1e-10 * np.abs(M_bf).max()
    ring = np.repeat(model.node_body == BODY_RING, 3)[i]
    blocks = interior_blocks(*(A.tocsr() for A in (K[i][:, i], M[i][:, i], K[i][:, b])))
    assert sorted(ring[blk.rows].all() for blk in blocks) == [False, True]
    assert all(ring[blk.rows].all() or not ring[blk.rows].any() for blk in blocks)


@pytest.mark.parametrize("h", [0, 1, 2])
def test_final_model_static_response_is_exact(small_quadratic, h):
    """Cyclic sector of harmonic h after all three steps: unit loads at every physical DoF."""
    model, kn, kt, rs = small_quadratic
    rh = rs.harmonics[h]
    Kc = contact_stiffness(model, kn, kt)
    T, independent = cyclic_transform(model.n_dofs, model.left_nodes, model.right_nodes,
                                      model.fixed_dofs, model.sector_angle, rh.sigma)
    physical = rs.partition.physical
    pos = np.searchsorted(independent, physical)
    assert np.array_equal(independent[pos], physical)
    loads = np.zeros((len(independent), len(physical)), dtype=T.dtype)
    loads[pos, np.arange(len(physical))] = 1.0
    u_full = solve(project(T, model.K + Kc), loads)[pos]
    K_stuck, _ = stuck_matrices(rh, kn, kt)
    n_p = rh.n_physical
    rhs = np.zeros((rh.size, n_p), dtype=complex)
    rhs[:n_p] = np.eye(n_p)
    u_red = np.linalg.solve(K_stuck, rhs)[:n_p]
    assert np.linalg.norm(u_red - u_full) / np.linalg.norm(u_full) < 1e-8
