"""Structure of the reduced model: Hermitian positive matrices, the ring's rigid motions, DoF sets,
the modal data the nonlinear stage receives, the NetCDF contract and argument errors."""
import numpy as np
import pytest
import scipy.linalg as sla

from ringdamper.fem.contact_law import stuck_pair_stiffness
from ringdamper.fem.model import build_model
from ringdamper.geometry.sector import BODY_RING, build_sector
from ringdamper.io import check_contract, read_netcdf, write_netcdf
from ringdamper.reduction import (
    eigenfrequencies,
    modal_basis,
    modal_stuck_frequencies,
    reduce_sector,
    reduced_dataset,
    stuck_frequencies,
    stuck_matrices,
)
from ringdamper.reduction.partition import partition
from ringdamper.reduction.stage import reduction_sizes

EO = 27


@pytest.fixture(scope="module")
def small(small_config, campaign_config):
    model = build_model(build_sector(small_config, (-0.4, 0.8, -0.2)), small_config)
    kn, kt = stuck_pair_stiffness(model.pairs.area, small_config["contact"])
    return model, kn, kt, reduce_sector(model, EO, n_harmonics=5, **reduction_sizes(campaign_config))


def test_partition(small):
    model, *_ = small
    part = partition(model)
    right = np.isin(part.right, part.physical)
    assert not right.any()
    assert len(part.right) == len(part.left) + np.isin(3 * part.left_nodes, part.physical).sum() * 3
    assert not np.isin(part.boundary, model.fixed_dofs).any()
    assert len(np.unique(part.boundary)) == len(part.boundary)
    assert len(part.boundary) + len(part.interior) == len(part.free)


def test_harmonics_and_nodal_diameters(small):
    *_, rs = small
    assert [rh.nd for rh in rs.harmonics] == [0, 3, 6, 9, 12, 15]
    assert np.isrealobj(rs.harmonics[0].K) and np.isrealobj(rs.harmonics[5].K)   # sigma = 0, pi
    assert np.iscomplexobj(rs.harmonics[1].K)


@pytest.mark.parametrize("h", range(6))
def test_hermitian_positive(small, h):
    model, kn, kt, rs = small
    rh = rs.harmonics[h]
    for A in (rh.K, rh.M):
        assert np.linalg.norm(A - A.conj().T) <= 1e-13 * np.linalg.norm(A)
    sla.cholesky(rh.M)                               # positive definite
    w2 = sla.eigvalsh(rh.K)
    assert w2.min() > -1e-9 * w2.max()               # positive semi-definite
    K_stuck, _ = stuck_matrices(rh, kn, kt)
    sla.cholesky(K_stuck)                            # stuck contact: positive definite


@pytest.mark.parametrize("coarse", [False, True])
def test_nd0_rigid_modes_are_the_rings(small, coarse):
    """Exactly two zero modes at ND 0 with free contact, also for very few interface modes (the static
    lift of the face DoFs keeps rigid motions exact), none with stuck contact."""
    model, kn, kt, rs = small
    if coarse:
        rs = reduce_sector(model, EO, harmonics=[0], n_fi=5, n_if=2)
    rh = rs.harmonics[0]
    w2, phi = sla.eigh(rh.K, rh.M)
    scale = w2[2]
    assert np.sum(np.abs(w2) < 1e-8 * scale) == 2      # exactly two, no spurious ones
    assert w2[2] > 1e-4 * w2[3]
    # they are the ring's rotation about Z and axial translation (blisk still)
    part = rs.partition
    nodes = part.physical // 3
    comp = part.physical % 3
    ring = model.node_body[nodes] == BODY_RING
    x = model.nodes[nodes]
    rot = np.where(comp == 0, -x[:, 1], np.where(comp == 1, x[:, 0], 0.0)) * ring
    trans = (comp == 2) * ring
    rigid = np.column_stack([rot, trans])
    shapes = phi[:rh.n_physical, :2]
    coef, *_ = np.linalg.lstsq(rigid, shapes, rcond=None)
    assert np.linalg.norm(rigid @ coef - shapes) < 1e-6 * np.linalg.norm(shapes)
    # stuck contact: none
    assert stuck_frequencies(rh, kn, kt, 1)[0] > 10.0


@pytest.mark.parametrize("h", [0, 1, 5])
def test_modal_data_reproduce_stuck_model(small, h):
    """The stored modal basis is complete: stuck frequencies from it equal the matrices'."""
    model, kn, kt, rs = small
    rh = rs.harmonics[h]
    mb = modal_basis(rh, rs.response_index)
    assert mb.omega2.shape == (rh.size,) and mb.contact.shape == (rh.size, len(model.pairs), 3)
    kn_open = kn * (np.arange(len(kn)) % 3 != 0)
    direct = stuck_frequencies(rh, kn_open, kt, 20)
    modal = modal_stuck_frequencies(mb.omega2, mb.contact, kn_open, kt, 20)
    assert np.allclose(modal, direct, rtol=1e-9)
    free = eigenfrequencies(rh.K, rh.M, 20)      # rigid modes (ND 0) agree to round-off (0.1 Hz)
    assert np.allclose(np.sign(mb.omega2[:20]) * np.sqrt(np.abs(mb.omega2[:20])) / (2 * np.pi),
                       free, rtol=1e-9, atol=0.1)


def test_contact_and_response_coordinates(small):
    model, kn, kt, rs = small
    part = rs.partition
    assert part.physical[rs.response_index] == model.response_dof()
    # B picks d = F (u_ring - u_blisk): a unit axial ring motion opens nothing, slides along t2
    y = np.zeros(rs.harmonics[0].size)
    ring_z = np.isin(part.physical, 3 * model.pairs.ring_node + 2)
    y[:rs.harmonics[0].n_physical][ring_z] = 1.0
    d = (rs.harmonics[0].B @ y).reshape(-1, 3)
    assert np.allclose(d, [0.0, 0.0, 1.0], atol=1e-14)


def test_netcdf_contract(small, tmp_path):
    model, kn, kt, rs = small
    ds = reduced_dataset(rs, (-0.4, 0.8, -0.2))
    check_contract(ds)
    path = tmp_path / "reduced.nc"
    write_netcdf(ds, path)
    back = read_netcdf(path)
    n = rs.harmonics[0].size
    assert dict(back.sizes) == {"harmonic": 6, "mode": n, "pair": len(model.pairs), "direction": 3}
    assert list(back.nodal_diameter.values) == [0, 3, 6, 9, 12, 15]
    counts = rs.dof_counts
    assert (back.attrs["dofs_full"], back.attrs["dofs_craig_bampton"], back.attrs["dofs_mead"],
            back.attrs["dofs_interface"]) == (counts["full"], counts["craig_bampton"], counts["mead"],
                                              counts["interface"])
    assert back.attrs["n_fixed_interface_modes"] == rs.harmonics[0].n_fi
    # frequencies computed from the file alone
    contact = back.contact_shape_real.values[1] + 1j * back.contact_shape_imag.values[1]
    f_file = modal_stuck_frequencies(back.omega2.values[1], contact, kn, kt, 5)
    assert np.allclose(f_file, stuck_frequencies(rs.harmonics[1], kn, kt, 5), rtol=1e-9)


def test_argument_errors(small):
    model, *_ = small
    with pytest.raises(ValueError, match="n_if"):
        reduce_sector(model, EO, harmonics=[0], n_fi=80, n_if=10_000)
    with pytest.raises(ValueError, match="n_fi"):
        reduce_sector(model, EO, harmonics=[0], n_fi=10_000, n_if=40)
