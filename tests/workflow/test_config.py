"""Bad configuration values give one clear message naming the field and the allowed range."""
import re

import pytest

from ringdamper.config import ConfigError, validate_config


def _error(config) -> str:
    with pytest.raises(ConfigError) as info:
        validate_config(config)
    return str(info.value)


def test_campaign_config_is_valid(campaign_config):
    assert campaign_config["geometry"]["n_sectors"] == 30


def test_kappa_out_of_range_names_field_and_range(config):
    config["sampling"]["named_validation"][1][2] = 1.5
    msg = _error(config)
    assert "sampling.named_validation[1][2]" in msg
    assert "1.5" in msg and "[-1, 1]" in msg


def test_unknown_key_is_rejected(config):
    config["mesh"]["n_theta_per_thirds"] = 3
    msg = _error(config)
    assert "mesh" in msg and "n_theta_per_thirds" in msg and "unknown key" in msg


def test_wrong_type(config):
    config["mesh"]["n_r_web"] = "four"
    msg = _error(config)
    assert "mesh.n_r_web" in msg and "wrong type" in msg


@pytest.mark.parametrize("field", [("material", "young_modulus"), ("material", "density"),
                                   ("geometry", "ring", "thickness")])
def test_non_positive_physical_quantity(config, field):
    node = config
    for key in field[:-1]:
        node = node[key]
    node[field[-1]] = 0.0
    msg = _error(config)
    assert ".".join(field) in msg and "(0, +inf)" in msg


def test_poisson_ratio_range(config):
    config["material"]["poisson_ratio"] = 0.5
    assert re.search(r"material\.poisson_ratio = 0\.5 is out of range: allowed \(-1, 0\.5\)", _error(config))


def test_ring_must_fit_under_the_rim(config):
    config["geometry"]["ring"]["axial_center"] = 0.0
    msg = _error(config)
    assert "geometry.ring.axial_center" in msg and "must lie in" in msg


@pytest.mark.parametrize("path, value, expected", [
    (("geometry", "ring", "radial_clearance"), -5.1e-5,
     "geometry.ring.radial_clearance = -5.1e-05 is out of range: allowed [-5e-05, 0.001]"),
    (("geometry", "disk", "arm_length"), 0.009,
     "geometry.disk.arm_length = 0.009 is out of range: allowed [0.01, 0.03]"),
    (("studies", "contact_state", "radial_clearance"), [0.0, -1e-4],
     "studies.contact_state.radial_clearance[1] = -0.0001 is out of range: allowed [-5e-05, 0.001]"),
    (("studies", "contact_state", "backbone_clearance"), [-6e-5],
     "studies.contact_state.backbone_clearance[0] = -6e-05 is out of range: allowed [-5e-05, 0.001]"),
    (("studies", "contact_state", "arm_length"), [0.02, 0.035],
     "studies.contact_state.arm_length[1] = 0.035 is out of range: allowed [0.01, 0.03]"),
    (("studies", "contact_state", "arm_thickness"), [0.006, 0.002],
     "studies.contact_state.arm_thickness[1] = 0.002 must lie in (0.0025, 0.0351)"),
    (("studies", "contact_state", "arm_thickness"), [0.04],
     "studies.contact_state.arm_thickness[0] = 0.04 must lie in (0.0025, 0.0351)"),
])
def test_clearance_and_groove_support_ranges(config, path, value, expected):
    """Interference beyond 50 µm, arms outside 10-30 mm or thinner than the deepest groove (or
    reaching the blade root) are refused, naming the field and the allowed range."""
    node = config
    for key in path[:-1]:
        node = node[key]
    node[path[-1]] = value
    assert expected in _error(config)


def test_ring_moves_with_the_arm(config):
    """The study's arm lengths keep the ring under the arm: an off-centre ring that fits on the
    configured 20 mm arm no longer fits on a 10 mm one (it moves with the arm's centre, by -5 mm)."""
    from ringdamper.config import ring_axial_center

    assert ring_axial_center(config["geometry"], 0.010) == pytest.approx(0.03125, abs=1e-12)
    config["geometry"]["ring"]["axial_center"] = 0.0410     # 0.55 mm from the 20 mm arm's tip
    config["studies"]["contact_state"]["arm_length"] = [0.020, 0.030]
    validate_config(config)
    config["studies"]["contact_state"]["arm_length"] = [0.010, 0.020]
    msg = _error(config)
    assert "studies.contact_state.arm_length[0] = 0.01: ring axial_center = 0.036 must lie in (0.03075, 0.03175)" in msg
    assert "arm_length[1]" not in msg


def test_every_problem_is_listed(config):
    config["material"]["density"] = -1.0
    config["operation"]["engine_order"] = 0
    msg = _error(config)
    assert "material.density" in msg and "operation.engine_order" in msg


@pytest.mark.parametrize("key, value, expected", [
    ("target_amplitudes", [1e-4, 5e-5], "frf.target_amplitudes = [0.0001, 5e-05] must be strictly increasing"),
    ("target_amplitudes", [-1e-4], "frf.target_amplitudes[0] = -0.0001 is out of range: allowed (0, 0.01]"),
    ("frequency_band", [1.01, 1.02], "frf.frequency_band = [1.01, 1.02] must bracket 1"),
    ("frequency_band", [0.4, 1.1], "frf.frequency_band[0] = 0.4 is out of range: allowed [0.5, 1.5]"),
])
def test_forced_response_settings(config, key, value, expected):
    config["frf"][key] = value
    assert expected in _error(config)
