"""The last-point study's read-out of the onset of separation (the indicator itself:
tests/nonlinear/test_separation.py)."""
import numpy as np
import pytest
import xarray as xr

from ringdamper.studies.last_point import onset_of_separation


def test_onset_is_read_where_the_ratio_crosses_zero():
    alpha = np.array([1.0, 2.0, 4.0, 8.0])
    ds = xr.Dataset({"normal_force_ratio_min": ("amplitude", [0.9, 0.4, -0.4, -1.0])},
                    coords={"amplitude": alpha})
    assert onset_of_separation(ds) == pytest.approx(np.sqrt(2.0 * 4.0))   # midway in log α
    ds["normal_force_ratio_min"][:] = [0.9, 0.8, 0.7, 0.6]
    assert np.isnan(onset_of_separation(ds))
