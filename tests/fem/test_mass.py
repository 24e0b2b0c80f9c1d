"""Masses: the ring against the analytic annular sector, the blisk independent of the mesh."""
import copy

import numpy as np
import pytest

from ringdamper.fem.model import build_model
from ringdamper.geometry.sector import BODY_RING, build_sector


def _body_masses(config):
    model = build_model(build_sector(config, (0.0, 0.0, 0.0)), config)
    ones = np.zeros(model.n_dofs)
    ones[0::3] = 1.0  # rigid translation along x
    ring = np.repeat(model.node_body == BODY_RING, 3)
    m_ring = ones[ring] @ (model.M[ring][:, ring] @ ones[ring])
    m_total = ones @ (model.M @ ones)
    return m_ring, m_total - m_ring


def test_ring_mass_matches_annular_sector(campaign_config):
    g = campaign_config["geometry"]
    rc, t, w = g["disk"]["contact_radius"], g["ring"]["thickness"], g["ring"]["width"]
    exact = campaign_config["material"]["density"] * np.pi / g["n_sectors"] * (rc**2 - (rc - t) ** 2) * w
    m_ring, _ = _body_masses(campaign_config)
    assert m_ring == pytest.approx(exact, rel=1e-3)


def test_blisk_mass_is_mesh_independent(campaign_config):
    fine = copy.deepcopy(campaign_config)
    for key in ("n_theta_per_third", "n_r_web", "n_r_rim", "n_z_front", "n_z_ring", "n_blade_height"):
        fine["mesh"][key] *= 2
    _, coarse_mass = _body_masses(campaign_config)
    _, fine_mass = _body_masses(fine)
    assert coarse_mass == pytest.approx(fine_mass, rel=1e-2)
    assert 1.0 < coarse_mass < 3.0  # kg: a 12 deg titanium sector of this size
