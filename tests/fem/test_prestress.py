"""Prestress: the SVK tangent is the derivative of the internal force; blades stiffen with speed."""
import numpy as np
import pytest

from ringdamper.fem.elasticity import internal_force, tangent_stiffness
from ringdamper.fem.model import build_model, stuck_contact_stiffness
from ringdamper.fem.prestress import prestressed_stiffness, rpm_to_rad_s, static_centrifugal
from ringdamper.geometry.sector import build_sector
from ringdamper.modal.analysis import FamilyClassifier, family_frequency, labelled_modes
from ringdamper.studies.hub_calibration import crossing_speed


@pytest.fixture(scope="module")
def small_model(small_config):
    config = {**small_config, "mesh": {**small_config["mesh"], "element_order": 2}}
    return build_model(build_sector(config, (0.5, -0.2, 0.1)), config), config


def test_tangent_matches_finite_difference_of_internal_force(small_model):
    model, config = small_model
    mat = config["material"]
    E, nu = mat["young_modulus"], mat["poisson_ratio"]
    Kc = stuck_contact_stiffness(model, config["contact"])
    # a large centrifugal state (10x operating speed) so that the nonlinear terms are not negligible
    u0 = static_centrifugal(model, 10 * rpm_to_rad_s(2081.0), Kc)
    rng = np.random.default_rng(0)
    du = rng.standard_normal(model.n_dofs) * np.abs(u0).max()
    KT = tangent_stiffness(model.basis, E, nu, u0)
    eps = 1e-4
    fd = (internal_force(model.basis, E, nu, u0 + eps * du)
          - internal_force(model.basis, E, nu, u0 - eps * du)) / (2 * eps)
    exact = KT @ du
    assert np.linalg.norm(fd - exact) / np.linalg.norm(exact) < 1e-6
    # and the geometric part matters: the linear stiffness alone misses it by far more
    K0 = tangent_stiffness(model.basis, E, nu)
    assert np.linalg.norm(K0 @ du - exact) / np.linalg.norm(exact) > 1e-3


def test_internal_force_is_linear_elastic_for_small_displacements(small_model):
    model, config = small_model
    mat = config["material"]
    u = np.random.default_rng(1).standard_normal(model.n_dofs) * 1e-12  # strains ~1e-9
    f = internal_force(model.basis, mat["young_modulus"], mat["poisson_ratio"], u)
    assert np.linalg.norm(f - model.K @ u) / np.linalg.norm(model.K @ u) < 1e-6


def test_blade_families_stiffen_with_speed(campaign_config):
    model = build_model(build_sector(campaign_config, (0.0, 0.0, 0.0)), campaign_config)
    Kc = stuck_contact_stiffness(model, campaign_config["contact"])
    clf = FamilyClassifier(model)
    rows = []
    for omega in (0.0, 1.2 * rpm_to_rad_s(2081.0)):
        f, labels, _ = labelled_modes(model, prestressed_stiffness(model, omega, Kc), 3, 6, clf)
        rows.append({fam: family_frequency(f, labels, fam) for fam in ("1B", "1T", "2B")})
    for fam in ("1B", "1T", "2B"):
        assert np.isfinite(rows[0][fam]) and rows[1][fam] > rows[0][fam], fam
    # Southwell: the flexible 1B rises most in relative terms
    rise = {fam: rows[1][fam] / rows[0][fam] - 1 for fam in rows[0]}
    assert rise["1B"] > rise["2B"] > 0


def test_calibrated_crossing_is_at_operating_speed(campaign_config):
    speed, freq = crossing_speed(campaign_config)
    assert speed == pytest.approx(2081.0, rel=0.03)
    assert freq == pytest.approx(27 * speed / 60, rel=1e-9)
