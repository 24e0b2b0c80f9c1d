"""Static contact on the real sector: rigid-groove and free-ring oracles, KKT, scaling."""
import copy

import numpy as np
import pytest

from ringdamper.fem.cyclic import cyclic_transform, project
from ringdamper.fem.elasticity import centrifugal_load
from ringdamper.fem.linalg import solve
from ringdamper.fem.model import build_model, node_dofs
from ringdamper.fem.prestress import rpm_to_rad_s, spin_mass
from ringdamper.geometry.sector import BODY_RING, build_sector
from ringdamper.static.stage import solve_static, static_dataset
from ringdamper.studies.mesh_convergence import refined

EXTREMES = [(0, 0, 0), (1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1), (1, -1, -1)]


def _model(config, kappa=(0.0, 0.0, 0.0)):
    return build_model(build_sector(config, kappa), config)


def _radial_sums(model, result, speed_rpm):
    """(sum of N n.e_r over the pairs, integral of rho Omega^2 r over the ring)."""
    f = centrifugal_load(model.basis, model.material["density"], rpm_to_rad_s(speed_rpm)).reshape(-1, 3)
    ring = model.node_body == BODY_RING
    x = model.nodes[ring]
    body = np.sum(f[ring][:, :2] * x[:, :2] / np.linalg.norm(x[:, :2], axis=1)[:, None])
    p = model.pairs.position[:, :2]
    e_r = p / np.linalg.norm(p, axis=1)[:, None]
    contact = np.sum(result.N0 * np.sum(model.pairs.frame[:, 0, :2] * e_r, axis=1))
    return contact, body


@pytest.mark.parametrize("kappa", [(0, 0, 0), (1, -1, -1), (-1, 1, 1)])
def test_rigid_groove_carries_the_ring_centrifugal_force(config, kappa):
    """Exact contact on a rigid groove: the pairs carry the ring's centrifugal force, no gap opens.

    With nu = 0 no hoop force arises, so the balance is local and the oracle exact; with nu = 0.33
    the radial compression of the ring induces a Poisson hoop compression nu sigma_r whose
    resultant over the cuts pushes outward: the pairs then carry slightly more (0.1-0.3 %).
    """
    config["static"]["method"] = "lagrange"
    config["material"]["poisson_ratio"] = 0.0
    model = _model(config, kappa)
    result, _ = solve_static(model, config, rigid_blisk=True)
    assert result.status == 0
    contact, body = _radial_sums(model, result, config["operation"]["speed_rpm"])
    assert contact == pytest.approx(body, rel=1e-3)
    assert np.all(result.gap < 1e-15) and np.all(result.in_contact)  # m: round-off of a closed set
    assert result.complementarity < 1e-10

    config["material"]["poisson_ratio"] = 0.33
    model = _model(config, kappa)
    result, _ = solve_static(model, config, rigid_blisk=True)
    contact, body = _radial_sums(model, result, config["operation"]["speed_rpm"])
    assert 0.0 < contact / body - 1.0 < 5e-3


def test_free_ring_grows_like_a_thin_ring(campaign_config):
    """Contact removed: radial growth = rho Omega^2 R^3 / E (thin ring) to 2 %, converged in the mesh."""
    omega = rpm_to_rad_s(campaign_config["operation"]["speed_rpm"])
    growth = []
    for factor in (1, 2):
        cfg = refined(campaign_config, factor)
        model = _model(cfg)
        ring = np.flatnonzero(model.node_body == BODY_RING)
        x = model.nodes[ring]
        gauge = ring[np.argmin(np.abs(np.arctan2(x[:, 1], x[:, 0])))]  # rotation about Z and axial drift
        fixed = np.union1d(node_dofs(np.flatnonzero(model.node_body != BODY_RING)), [3 * gauge + 1, 3 * gauge + 2])
        T, _ = cyclic_transform(model.n_dofs, model.left_nodes, model.right_nodes, fixed,
                                model.sector_angle, 0.0)
        K = project(T, model.K - omega**2 * spin_mass(model))
        u = (T @ solve(K, T.T @ centrifugal_load(model.basis, 4430.0, omega))).reshape(-1, 3)[ring]
        growth.append(np.mean(np.sum(u[:, :2] * x[:, :2], axis=1) / np.hypot(x[:, 0], x[:, 1])))
    g = cfg["geometry"]
    radius = g["disk"]["contact_radius"] - g["ring"]["thickness"] / 2
    thin_ring = cfg["material"]["density"] * omega**2 * radius**3 / cfg["material"]["young_modulus"]
    assert growth[0] == pytest.approx(thin_ring, rel=0.02)
    assert growth[0] == pytest.approx(growth[1], rel=1e-4)


@pytest.mark.parametrize("kappa", EXTREMES)
def test_kkt_and_ring_equilibrium(campaign_config, kappa):
    model = _model(campaign_config, kappa)
    result, prob = solve_static(model, campaign_config)
    assert result.status == 0, result.reason
    assert np.all(result.N0 >= 0) and np.all(result.gap >= 0)
    assert np.max(np.abs(result.N0 * result.gap)) <= 1e-12 * result.N0.max()
    lam = np.column_stack([result.N0, result.tangential]).ravel()
    residual = prob.K @ result.u + prob.G.T @ lam - prob.f
    independent_ring = (np.abs(prob.T).T @ np.repeat(model.node_body == BODY_RING, 3).astype(float)) > 0
    assert np.linalg.norm(residual[independent_ring]) <= 1e-8 * np.linalg.norm(prob.f[independent_ring])
    ds = static_dataset(model, result, prob, kappa, campaign_config["operation"]["speed_rpm"])
    assert ds.attrs["status"] == 0 and ds.N0.attrs["units"] == "N"


def test_no_speed_no_preload_and_quadratic_growth(campaign_config):
    model = _model(campaign_config)
    at_rest, _ = solve_static(model, campaign_config, speed_rpm=0.0)
    assert at_rest.status == 0 and np.all(at_rest.N0 == 0.0)
    slow, _ = solve_static(model, campaign_config, speed_rpm=1000.0)
    fast, _ = solve_static(model, campaign_config, speed_rpm=2000.0)
    assert np.array_equal(slow.in_contact, fast.in_contact)
    # N0 ~ Omega^2 while the contact set is fixed (spin softening, ~rho Omega^2 r^2 / E ~ 1e-4, aside)
    assert fast.N0 == pytest.approx(4.0 * slow.N0, rel=2e-3)


def test_absurd_stiffness_is_a_recorded_failure(campaign_config):
    model = _model(campaign_config)
    result, prob = solve_static(model, campaign_config, kn=np.nan)
    assert result.status != 0 and "kn" in result.reason
    ds = static_dataset(model, result, prob, (0, 0, 0), 2081.0)
    assert ds.attrs["status"] != 0 and ds.attrs["reason"] == result.reason


def test_a_failed_solve_writes_the_mesh_with_nan_fields(small_config, tmp_path):
    """A geometry whose static solve raises (here an unknown method) gives status 99 with the reason,
    and a static.vtu of its mesh whose fields are NaN (read back with meshio)."""
    import meshio

    from ringdamper.io import write_vtu
    from ringdamper.static.stage import run_static

    cfg = {**small_config, "static": {**small_config["static"], "method": "no-such-method"}}
    ds, model, fields = run_static(cfg, (0.0, 0.0, 0.0))
    assert ds.attrs["status"] == 99 and "no-such-method" in ds.attrs["reason"]
    write_vtu(model, tmp_path / "static.vtu", point_data=fields)
    mesh = meshio.read(tmp_path / "static.vtu")
    assert len(mesh.points) == len(model.nodes) > 0
    assert mesh.point_data["displacement"].shape == (len(model.nodes), 3)
    assert all(np.all(np.isnan(mesh.point_data[k])) for k in ("displacement", "N0", "gap"))


def test_a_failed_static_file_has_the_variables_of_a_solved_one(small_config, tmp_path):
    """static.nc is declared once: a failed geometry's file has a solved one's variables, dimensions
    and attributes, every value NaN (in_contact -1), status 99 and the reason; it reads back."""
    from ringdamper.io import read_netcdf, write_netcdf
    from ringdamper.static.stage import run_static

    solved, model, _ = run_static(small_config, (0.0, 0.0, 0.0))
    cfg = {**small_config, "static": {**small_config["static"], "method": "no-such-method"}}
    failed, _, _ = run_static(cfg, (0.0, 0.0, 0.0))
    write_netcdf(failed, tmp_path / "static.nc")
    back = read_netcdf(tmp_path / "static.nc", "static")
    assert solved.attrs["status"] == 0 and back.attrs["status"] == 99
    assert set(back.data_vars) == set(solved.data_vars) and dict(back.sizes) == dict(solved.sizes)
    assert set(solved.attrs) <= set(back.attrs)
    for name, var in back.data_vars.items():
        assert var.dtype == solved[name].dtype, name
        if name == "in_contact":
            assert np.all(var.values == -1)
        else:
            assert np.all(np.isnan(var.values)), name


@pytest.mark.parametrize("method", ["penalty", "lagrange"])
def test_kkt_is_exact_with_pairs_open(campaign_config, method):
    """A radial clearance of 38 um on kappa2 = +1 opens part of the pairs (about 0.6 of them): the
    returned state is still exactly complementary (docs/testing.md), open pairs carry gap = g0 - d_n,
    closed ones the normal law, and the ring is in equilibrium."""
    cfg = copy.deepcopy(campaign_config)
    cfg["static"]["method"] = method
    cfg["geometry"]["ring"]["radial_clearance"] = 38e-6
    model = _model(cfg, (0, 1, 0))
    result, prob = solve_static(model, cfg)
    assert result.status == 0, result.reason
    closed = result.in_contact
    assert 0 < closed.sum() < closed.size
    assert np.all(result.gap[closed] == 0.0) and np.all(result.N0[~closed] == 0.0)
    assert np.all(result.N0 >= 0) and np.all(result.gap >= 0)
    d_n = result.relative_displacement[:, 0]
    scale = np.max(np.abs(result.u))                               # m, round-off of d_n is eps x this
    assert np.all(prob.g0[~closed] - d_n[~closed] > 0)
    assert result.gap[~closed] == pytest.approx(prob.g0[~closed] - d_n[~closed], abs=1e-12 * scale)
    if method == "penalty":
        assert result.N0[closed] == pytest.approx(prob.kn[closed] * (d_n[closed] - prob.g0[closed]), rel=1e-10)
    else:
        assert np.max(np.abs(d_n[closed] - prob.g0[closed])) <= 1e-9 * scale
    lam = np.column_stack([result.N0, result.tangential]).ravel()
    residual = prob.K @ result.u + prob.G.T @ lam - prob.f
    assert np.linalg.norm(residual) <= 1e-8 * np.linalg.norm(prob.f)


@pytest.mark.parametrize("method", ["penalty", "lagrange"])
def test_interference_fit_preloads_a_ring_like_a_thin_ring(config, method):
    """The default ring pressed δ = 50 µm into a rigid groove, at rest (no centrifugal load), nu = 0:
    a uniform pressure p closes every pair and compresses the ring by u = p R_o R_m / (E t) (thin
    ring: hoop force p R_o per unit width, strain u / R_m; R_o the groove radius, R_m the ring's mean
    radius, t its thickness). Penalty (k per area): p = k (δ − u), so p = δ / (R_o R_m / (E t) + 1/k);
    exact law: u = δ, p = δ E t / (R_o R_m). To 1e-3 (the thin-ring closed form; 4e-5 is seen), and
    pair by pair the penalty law N0 = kn (interference + closure) = kn (d_n − g0) to round-off."""
    delta = 50e-6
    config["static"]["method"] = method
    config["material"]["poisson_ratio"] = 0.0
    config["geometry"]["ring"]["radial_clearance"] = -delta
    model = _model(config)
    result, prob = solve_static(model, config, speed_rpm=0.0, rigid_blisk=True)
    assert result.status == 0, result.reason
    assert np.all(result.in_contact) and np.all(result.gap == 0.0)
    assert prob.g0 == pytest.approx(-delta, rel=1e-12)
    g = config["geometry"]
    r_o, t = g["disk"]["contact_radius"], g["ring"]["thickness"]
    compliance = r_o * (r_o - t / 2) / (config["material"]["young_modulus"] * t)
    k = config["contact"]["normal_stiffness_per_area"]
    p = delta / (compliance + (1.0 / k if method == "penalty" else 0.0))
    pressure = result.N0 / model.pairs.area
    assert np.sum(result.N0) / np.sum(model.pairs.area) == pytest.approx(p, rel=1e-3)
    assert np.ptp(pressure) <= 1e-3 * p                               # axisymmetric: uniform
    d_n = result.relative_displacement[:, 0]
    if method == "penalty":
        assert result.N0 == pytest.approx(prob.kn * (d_n - prob.g0), rel=1e-10)
        assert result.penetration == pytest.approx(result.N0 / prob.kn, rel=1e-10)
    else:
        assert np.max(np.abs(d_n - prob.g0)) <= 1e-9 * delta


def test_clearance_gap_lies_along_the_pair_normal(campaign_config):
    """g0 = c (n . e_r): c on the cylindrical default ring, less on the flanks of kappa1's bump."""
    from ringdamper.static.stage import clearance_gaps

    assert clearance_gaps(_model(campaign_config), 2e-5) == pytest.approx(2e-5, rel=1e-12)
    g0 = clearance_gaps(_model(campaign_config, (1, 0, 0)), 2e-5)
    assert np.all(g0 <= 2e-5 * (1 + 1e-12)) and g0.min() < 0.99 * 2e-5
