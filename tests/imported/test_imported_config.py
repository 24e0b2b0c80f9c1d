"""The configuration of an imported sector: schema, cross-field rule and the mesh path's folder."""
import copy

import pytest
import yaml

from ringdamper.config import REPO, ConfigError, load_config, validate_config

EXAMPLE = REPO / "docs" / "examples" / "imported" / "config.yaml"


def _merged(campaign_config):
    config = copy.deepcopy(campaign_config)
    user = yaml.safe_load(EXAMPLE.read_text())
    config["geometry"].update(user["geometry"])
    config["imported"] = user["imported"]
    return config


def test_a_relative_mesh_is_read_from_the_config_files_folder(campaign_config, tmp_path):
    config = _merged(campaign_config)
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "blisk.msh").write_text("$MeshFormat\n")
    (tmp_path / "sub" / "my.yaml").write_text(yaml.safe_dump(config))
    assert load_config(tmp_path / "sub" / "my.yaml")["imported"]["mesh"] == str(tmp_path / "sub" / "blisk.msh")


def test_a_missing_mesh_names_both_paths(campaign_config, tmp_path):
    config = _merged(campaign_config)
    (tmp_path / "my.yaml").write_text(yaml.safe_dump(config))
    with pytest.raises(ConfigError, match=r"imported.mesh = 'blisk.msh': no such file \(.*blisk.msh"):
        load_config(tmp_path / "my.yaml")


def test_source_imported_needs_the_imported_section(campaign_config):
    config = copy.deepcopy(campaign_config)
    config["geometry"]["source"] = "imported"
    with pytest.raises(ConfigError, match="imported: required when geometry.source = 'imported'"):
        validate_config(config)


@pytest.mark.parametrize("key, value, message", [
    ("length_unit", "inch", r"imported.length_unit = 'inch' is not allowed: choose one of \['m', 'mm'\]"),
    ("mesh", "sector.stl", "imported.mesh"),
    ("axis", [0.0, 0.0, 0.0], r"imported.axis = \[0.0, 0.0, 0.0\] must not be the zero vector"),
])
def test_bad_imported_values_are_named(campaign_config, key, value, message):
    config = _merged(campaign_config)
    config["imported"][key] = value
    with pytest.raises(ConfigError, match=message):
        validate_config(config)
