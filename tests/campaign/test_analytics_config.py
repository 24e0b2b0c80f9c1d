"""The surrogate, exploration and sensitivity sections: bad values are named before any job runs."""
import pytest

from ringdamper.config import ConfigError, validate_config


def _error(config) -> str:
    with pytest.raises(ConfigError) as info:
        validate_config(config)
    return str(info.value)


def test_local_box_outside_the_design_space(config):
    config["sensitivity"]["local_box"][0] = [0.9, 1.1]
    assert "sensitivity.local_box[0][1] = 1.1 is out of range: allowed [-1, 1]" in _error(config)


def test_local_box_reversed(config):
    config["sensitivity"]["local_box"][2] = [-0.9, -1.0]
    assert "sensitivity.local_box[2] = [-0.9, -1.0] must have low < high (kappa3)" in _error(config)


def test_levels_positive_and_increasing(config):
    config["sensitivity"]["levels"] = [1e-4, 0.0]
    assert "sensitivity.levels[1] = 0.0 is out of range: allowed (0, 0.01]" in _error(config)
    config["sensitivity"]["levels"] = [2e-4, 1e-4]
    assert "sensitivity.levels = [0.0002, 0.0001] must be strictly increasing" in _error(config)


def test_too_few_pce_samples_for_the_degree(config):
    config["sensitivity"]["pce_degree"] = 10  # C(13, 3) = 286 polynomials
    config["sensitivity"]["pce_samples"] = 200
    assert "pce_samples = 200 must be at least the 286 polynomials" in _error(config)


def test_min_training_above_the_training_set(config):
    config["sampling"]["design"] = "paper"
    config["surrogate"]["min_training"] = 101
    assert "surrogate.min_training = 101 exceeds the 100 training geometries" in _error(config)


def test_unknown_estimator(config):
    config["sensitivity"]["estimator"] = "sobol"
    assert "sensitivity.estimator = 'sobol' is not allowed" in _error(config)


def test_bad_transform_and_log_offset_are_named(config):
    config["surrogate"]["transform"] = {"zeta": "sqrt"}
    assert "surrogate.transform.zeta = 'sqrt' is not allowed: choose one of ['identity', 'log']" in _error(config)
    config["surrogate"]["transform"] = {"zeta": "log"}
    config["surrogate"]["log_offset"] = 0.0
    assert "surrogate.log_offset = 0.0 is out of range: allowed (0, +inf)" in _error(config)
