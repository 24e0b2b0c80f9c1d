"""Parametric sector mesh: Table 2 mapping, radial-only motion, constant topology, cyclic faces."""
import numpy as np
import pytest

from ringdamper.fem.model import build_model
from ringdamper.geometry.sector import build_sector
from ringdamper.geometry.shape import check_kappa, unit_bump

TABLE2 = {1: (-1.5e-3, 0.0, 2.5e-3), 2: (-2.0e-3, 0.0, 1.5e-3), 3: (-1.5e-3, 0.0, 1.0e-3)}


@pytest.fixture(scope="module")
def reference(campaign_config):
    return build_sector(campaign_config, (0.0, 0.0, 0.0))


def _cyl(points):
    return np.hypot(points[0], points[1]), np.arctan2(points[1], points[0]), points[2]


def _ring_surface_node(model, surface, theta):
    """Node of the ring's upper or lower surface at angle theta (any of the 27 nodes of a brick)."""
    r, t, _ = _cyl(model.nodes.T)
    cand = np.flatnonzero((model.node_body == 1) & np.isclose(t, theta, atol=1e-12))
    return cand[np.argmax(r[cand])] if surface == "upper" else cand[np.argmin(r[cand])]


def test_unit_bump_is_c1_with_unit_height():
    s = np.linspace(-1, 1, 20001)
    b = unit_bump(s)
    assert b.max() == pytest.approx(1.0, abs=1e-12) and b[0] == 0.0 and b[-1] == 0.0
    slope = np.gradient(b, s)
    assert np.max(np.abs(np.diff(slope))) < 1e-2  # no jump in slope anywhere (C^1)
    assert abs(slope[0]) < 1e-3 and abs(slope[-1]) < 1e-3


@pytest.mark.parametrize("level", [-1.0, 0.0, 1.0])
@pytest.mark.parametrize("which", [1, 2, 3])
def test_table2_central_nodes_move_by_delta_r(campaign_config, reference, which, level):
    kappa = [0.0, 0.0, 0.0]
    kappa[which - 1] = level
    model = build_model(build_sector(campaign_config, kappa), campaign_config)
    ref = build_model(reference, campaign_config)
    th = reference.half_angle
    expected = TABLE2[which][int(level) + 1]
    surface, centres = {1: ("upper", [0.0]), 2: ("lower", [-2 * th / 3, 2 * th / 3]),
                        3: ("lower", [0.0])}[which]
    r0 = np.hypot(*ref.nodes.T[:2])
    r1 = np.hypot(*model.nodes.T[:2])
    for theta in centres:
        node = _ring_surface_node(ref, surface, theta)
        assert r1[node] - r0[node] == pytest.approx(expected, abs=1e-13)


def test_nodes_move_only_radially_and_topology_is_constant(campaign_config, reference):
    rng = np.random.default_rng(3)
    for _ in range(3):
        kappa = rng.uniform(-1, 1, 3)
        sector = build_sector(campaign_config, kappa)
        assert sector.vertices.T.shape == reference.vertices.T.shape
        assert np.array_equal(sector.mesh.t, reference.mesh.t)
        _, t0, z0 = _cyl(reference.vertices.T)
        _, t1, z1 = _cyl(sector.vertices.T)
        assert np.allclose(t1, t0, atol=1e-13) and np.array_equal(z1, z0)


def test_kappa_out_of_range_is_a_clear_error(campaign_config):
    with pytest.raises(ValueError, match=r"kappa2 = 1.2 is out of range: allowed \[-1, 1\]"):
        check_kappa([0.0, 1.2, 0.0])
    with pytest.raises(ValueError, match="kappa3"):
        build_sector(campaign_config, [0.0, 0.0, -1.01])


@pytest.mark.parametrize("kappa", [(0.0, 0.0, 0.0), (1.0, -1.0, -1.0), (-1.0, 1.0, 1.0)])
def test_cyclic_faces_and_contact_pairs_coincide(campaign_config, kappa):
    model = build_model(build_sector(campaign_config, kappa), campaign_config)
    a = model.sector_angle
    rot = np.array([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1]])
    left, right = model.nodes[model.left_nodes], model.nodes[model.right_nodes]
    assert len(left) > 0 and np.max(np.abs(left @ rot.T - right)) < 1e-12
    assert np.max(np.abs(model.nodes[model.pairs.ring_node] - model.nodes[model.pairs.blisk_node])) < 1e-12
    # every pair once: no pair on the right cut, the frames are orthonormal and n points outward
    theta = np.arctan2(model.pairs.position[:, 1], model.pairs.position[:, 0])
    assert theta.max() < np.pi / 30 - 1e-9
    F = model.pairs.frame
    assert np.allclose(np.einsum("pij,pkj->pik", F, F), np.eye(3), atol=1e-12)
    assert np.all(np.einsum("pj,pj->p", F[:, 0, :2], model.pairs.position[:, :2]) > 0)


def test_every_element_has_the_same_orientation(campaign_config):
    sector = build_sector(campaign_config, (1.0, 1.0, -1.0))
    gauss = np.array([[0.1, 0.9], [0.1, 0.9], [0.1, 0.9]])
    pts = np.array(np.meshgrid(*gauss)).reshape(3, -1)
    det = sector.mesh.mapping().detDF(pts)
    assert np.all(det < 0) or np.all(det > 0)


def test_tip_node_is_the_leading_edge_blade_tip(campaign_config):
    model = build_model(build_sector(campaign_config, (0.0, 0.0, 0.0)), campaign_config)
    x = model.nodes[model.tip_node]
    blade = campaign_config["geometry"]["blade"]
    assert np.hypot(x[0], x[1]) == pytest.approx(blade["tip_radius"], abs=1e-5)
    assert x[2] == pytest.approx(-blade["chord"] / 2, abs=1e-12)


@pytest.mark.parametrize("value", [-6e-5, 2e-3])
def test_radial_clearance_out_of_range_names_the_field(campaign_config, value):
    """An interference beyond 50 µm or a ring loose by millimetres is refused before any meshing,
    naming the field and the allowed range."""
    import copy

    from ringdamper.config import ConfigError, validate_config

    cfg = copy.deepcopy(campaign_config)
    cfg["geometry"]["ring"]["radial_clearance"] = value
    with pytest.raises(ConfigError) as err:
        validate_config(cfg)
    assert "geometry.ring.radial_clearance" in str(err.value) and "allowed [-5e-05, 0.001]" in str(err.value)
