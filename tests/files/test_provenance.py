"""Every NetCDF written through ringdamper.io records its provenance: package and library versions,
the git commit, and the hash of exactly the configuration sections its rule passes (those the file
depends on)."""
import copy

import numpy as np
import pytest
import xarray as xr

from ringdamper.io import provenance, read_netcdf, variable, write_netcdf

LIBRARIES = ("ringdamper", "numpy", "scipy", "openturns")


def test_a_written_file_carries_versions_commit_and_the_config_hash(tmp_path, small_config):
    import numpy
    import openturns
    import scipy

    ds = xr.Dataset({"a": variable("i", [1.0, 2.0], "m", "a length")}, attrs={"kappa": np.array([0.1, 0, -1])})
    sections = {k: small_config[k] for k in ("material", "contact", "dnnm")}
    write_netcdf(ds, tmp_path / "f.nc", sections)
    attrs = read_netcdf(tmp_path / "f.nc").attrs
    assert attrs["numpy_version"] == numpy.__version__ and attrs["scipy_version"] == scipy.__version__
    assert attrs["openturns_version"] == openturns.__version__
    assert attrs["ringdamper_version"] == "0.1.0"
    assert len(attrs["git_commit"].split("+")[0]) in (40, len("unknown"))  # a sha1, or no git work tree
    assert attrs["config_sections"].split() == ["material", "contact", "dnnm"]
    assert len(attrs["config_sha256"]) == 64
    assert list(attrs["kappa"]) == [0.1, 0.0, -1.0]


@pytest.mark.parametrize("names", [("material", "geometry", "mesh", "operation", "reduction"),
                                   ("sampling", "contact", "dnnm", "surrogate"), ("studies",)])
def test_the_hash_follows_exactly_the_sections_a_file_depends_on(campaign_config, names):
    """Any change inside a passed section moves the hash; the order the sections are passed in and
    the sections not passed do not."""
    base = provenance({k: campaign_config[k] for k in names})["config_sha256"]
    assert provenance({k: campaign_config[k] for k in reversed(names)})["config_sha256"] == base
    for section in campaign_config:
        changed = copy.deepcopy(campaign_config)
        changed[section] = {"changed": True}
        moved = provenance({k: changed[k] for k in names})["config_sha256"] != base
        assert moved == (section in names), (names, section)


def test_without_a_configuration_the_software_is_still_recorded(tmp_path):
    ds = xr.Dataset({"a": variable("i", [1.0], "m", "a length")})
    write_netcdf(ds, tmp_path / "f.nc")
    attrs = read_netcdf(tmp_path / "f.nc").attrs
    assert {f"{lib}_version" for lib in LIBRARIES} | {"git_commit"} <= set(attrs)
    assert "config_sha256" not in attrs
