"""Every NetCDF written through ringdamper.io records its provenance: package and library versions,
the git commit, and the hash of exactly the configuration sections the file depends on."""
import copy

import numpy as np
import pytest
import xarray as xr

from ringdamper.io import CONFIG_SECTIONS, provenance, read_netcdf, variable, write_netcdf

LIBRARIES = ("ringdamper", "numpy", "scipy", "openturns")


def test_a_written_file_carries_versions_commit_and_the_config_hash(tmp_path, small_config):
    import numpy
    import openturns
    import scipy

    ds = xr.Dataset({"a": variable("i", [1.0, 2.0], "m", "a length")}, attrs={"kappa": np.array([0.1, 0, -1])})
    write_netcdf(ds, tmp_path / "f.nc", small_config, "dnnm")
    attrs = read_netcdf(tmp_path / "f.nc").attrs
    assert attrs["numpy_version"] == numpy.__version__ and attrs["scipy_version"] == scipy.__version__
    assert attrs["openturns_version"] == openturns.__version__
    assert attrs["ringdamper_version"] == "0.1.0"
    assert len(attrs["git_commit"].split("+")[0]) in (40, len("unknown"))  # a sha1, or no git work tree
    assert attrs["config_sections"].split() == list(CONFIG_SECTIONS["dnnm"])
    assert len(attrs["config_sha256"]) == 64
    assert list(attrs["kappa"]) == [0.1, 0.0, -1.0]


@pytest.mark.parametrize("rule", sorted(CONFIG_SECTIONS))
def test_the_hash_follows_exactly_the_sections_a_file_depends_on(campaign_config, rule):
    """On the full configuration (the test one leaves out the study sections)."""
    base = provenance(campaign_config, rule)["config_sha256"]
    for section in campaign_config:
        changed = copy.deepcopy(campaign_config)
        changed[section] = {"changed": True}
        moved = provenance(changed, rule)["config_sha256"] != base
        assert moved == (section in CONFIG_SECTIONS[rule]), (rule, section)


def test_without_a_configuration_the_software_is_still_recorded(tmp_path):
    ds = xr.Dataset({"a": variable("i", [1.0], "m", "a length")})
    write_netcdf(ds, tmp_path / "f.nc")
    attrs = read_netcdf(tmp_path / "f.nc").attrs
    assert {f"{lib}_version" for lib in LIBRARIES} | {"git_commit"} <= set(attrs)
    assert "config_sha256" not in attrs
