"""Stage files read by the rules: a truncated or foreign NetCDF is refused with a message naming the
file and what is wrong; the files the stages write pass their own check."""
import numpy as np
import pytest
import xarray as xr

from ringdamper.io import InputFileError, read_netcdf, variable, write_netcdf
from ringdamper.nonlinear.stage import failed_dnnm
from ringdamper.static.stage import failed_static


def tiny_reduced() -> xr.Dataset:
    """A reduced.nc-shaped dataset: 2 harmonics, 2 modes, 3 pairs, 3 directions."""
    rng = np.random.default_rng(0)
    dims = ("harmonic", "mode", "pair", "direction")
    shape = (2, 2, 3, 3)
    data = {"omega2": variable(("harmonic", "mode"), [[1e6, 4e6], [2e6, 5e6]], "rad2 s-2",
                               "modal eigenvalue omega_r^2")}
    for part in ("real", "imag"):
        data[f"contact_shape_{part}"] = variable(dims, rng.normal(size=shape), "m kg-0.5",
                                                 f"relative contact displacement of mode r ({part})")
        data[f"response_shape_{part}"] = variable(("harmonic", "mode"), rng.normal(size=(2, 2)),
                                                  "m kg-0.5", f"blade-tip Z value of mode r ({part})")
    return xr.Dataset(data, attrs={"n_sectors": 24, "engine_order": 1, "kappa": np.zeros(3)})


def test_a_written_reduced_file_reads_back(tmp_path):
    path = tmp_path / "reduced.nc"
    write_netcdf(tiny_reduced(), path)
    back = read_netcdf(path, "reduced")
    assert np.array_equal(back.contact_shape_real.values, tiny_reduced().contact_shape_real.values)


def test_a_truncated_file_is_refused_naming_it(tmp_path):
    path = tmp_path / "reduced.nc"
    write_netcdf(tiny_reduced(), path)
    data = path.read_bytes()
    path.write_bytes(data[: len(data) // 2])
    with pytest.raises(InputFileError, match=rf"{path}: truncated or not a NetCDF file"):
        read_netcdf(path, "reduced")


def test_a_foreign_netcdf_is_refused_naming_the_missing_variable(tmp_path):
    path = tmp_path / "reduced.nc"
    foreign = xr.Dataset({"temperature": variable("time", [280.0, 281.5], "K", "air temperature")},
                         attrs={"n_sectors": 24, "engine_order": 1})
    write_netcdf(foreign, path)
    with pytest.raises(InputFileError, match=rf"{path}: not a ringdamper reduced\.nc: omega2 missing"):
        read_netcdf(path, "reduced")
    with pytest.raises(InputFileError, match=r"not a ringdamper static\.nc: kappa missing"):
        read_netcdf(path, "static")


def test_a_failed_geometry_files_pass_their_check(tmp_path):
    """A failed dNNM file holds every variable a reader needs, and so does a failed static.nc."""
    config = {"dnnm": {"amplitude_min": 1e-6, "amplitude_max": 1e-4, "n_amplitudes": 4},
              "operation": {"speed_rpm": 2081.0}, "static": {"method": "penalty"}}
    write_netcdf(failed_dnnm(config, (0.1, 0.2, 0.3), "RuntimeError: no convergence", 3), tmp_path / "d.nc")
    assert np.all(read_netcdf(tmp_path / "d.nc", "dnnm").status.values == 99)
    write_netcdf(failed_static(config, (0.1, 0.2, 0.3), "ValueError: meshing", 0), tmp_path / "s.nc")
    assert read_netcdf(tmp_path / "s.nc", "static").attrs["status"] == 99
