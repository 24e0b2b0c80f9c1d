"""Aggregation of the per-geometry dnnm.nc files: failed geometries stay in the dataset, flagged,
and are left out of the Kriging fit with one warning each; too few training geometries stop the fit."""
import logging

import numpy as np
import pytest

from ringdamper.campaign.dataset import TrainingSetError, aggregate, check_training, usable_mask
from ringdamper.campaign.kriging import fit_campaign
from ringdamper.io import check_contract
from ringdamper.nonlinear.stage import failed_dnnm
from ringdamper.status import CHAIN_FAILED

from .synthetic import backbone, design, dnnm_dataset, write_campaign

ALPHA = np.geomspace(1e-6, 1e-4, 8)


@pytest.fixture
def campaign(tmp_path):
    """12 training + 3 validation geometries: t003 failed before the dNNM (status 99 with a reason),
    t005 not reached above the 6th amplitude (status 2), t007 held by the gauge at the top (status 3)."""
    samples = design(12, 3)
    config = {"dnnm": {"amplitude_min": ALPHA[0], "amplitude_max": ALPHA[-1], "n_amplitudes": ALPHA.size}}
    failed = failed_dnnm(config, [0.1, 0.2, 0.3], "RuntimeError: static solve failed: no convergence", 3)
    overrides = {"t003": failed,
                 "t005": dnnm_dataset(samples.iloc[5, 1:4].to_numpy(float), ALPHA, [0] * 6 + [2, 2]),
                 "t007": dnnm_dataset(samples.iloc[7, 1:4].to_numpy(float), ALPHA, [0] * 5 + [3] * 3)}
    for name in ("q_res_z", "zeta", "gamma", "omega0"):
        overrides["t005"][name].values[6:] = np.nan
    return samples, write_campaign(tmp_path, samples, ALPHA, overrides)


def test_aggregation_keeps_every_geometry_with_units_and_flags(campaign):
    samples, paths = campaign
    ds = aggregate(samples, paths)
    check_contract(ds)
    assert dict(ds.sizes) == {"geometry": 15, "amplitude": 8}
    assert list(ds.geometry.values) == list(samples.gid)
    assert np.allclose(ds.kappa1, samples.kappa1) and list(ds.split.values) == list(samples.split)
    assert ds.q_res_z.attrs["units"] == "m" and ds.gamma.attrs["units"] == "N"
    assert ds.jacobian_condition.attrs["units"] == "1" and "1e-6" in ds.ill_conditioned.attrs["long_name"]
    np.testing.assert_allclose(ds.zeta.sel(geometry="t001"),
                               backbone(samples.iloc[1, 1:4].to_numpy(float), ALPHA)["zeta"], rtol=1e-14)
    assert np.all(ds.status.sel(geometry="t003") == CHAIN_FAILED)
    assert "static solve failed" in ds.reason.sel(geometry="t003").item()
    assert ds.reason.sel(geometry="t005").item() == "6 converged, 2 not reached"
    assert ds.held.sel(geometry="t007").values.tolist() == [0] * 5 + [1] * 3
    assert ds.held.sum() == 3


def test_failed_points_are_excluded_with_one_warning_per_geometry(campaign, caplog):
    samples, paths = campaign
    ds = aggregate(samples, paths)
    with caplog.at_level(logging.WARNING):
        mask = usable_mask(ds)
    assert len(caplog.records) == 2
    assert "t003" in caplog.records[0].getMessage() and "static solve failed" in caplog.records[0].getMessage()
    assert "t005" in caplog.records[1].getMessage() and "2 of 8" in caplog.records[1].getMessage()
    assert not mask.sel(geometry="t003").any()
    assert mask.sel(geometry="t005").values.tolist() == [True] * 6 + [False] * 2
    assert mask.sel(geometry="t007").all()  # status 3 is valid data
    train = (ds.split == "training").values
    fit = fit_campaign(ds.isel(geometry=train), mask=mask.isel(geometry=train),
                       settings={"n_starts": 2, "min_training": 6})
    used = fit.training_mask.transpose("geometry", "amplitude")
    trained = set(fit.geometry.values[used.values.any(axis=1)])
    assert "t003" not in trained and used.sel(geometry="t007").all()
    assert int(fit.n_training.sel(output="zeta").values[0]) == 11
    assert int(fit.n_training.sel(output="zeta").values[-1]) == 10


def test_too_few_training_geometries_name_the_missing_ones(campaign):
    samples, paths = campaign
    ds = aggregate(samples, paths)
    mask = usable_mask(ds)
    check_training(ds, mask, 10)  # 10 usable at the top amplitudes: enough
    with pytest.raises(TrainingSetError, match=r"only 10 usable training geometries.*min_training = 11") as err:
        check_training(ds, mask, 11)
    assert "t003 (RuntimeError: static solve failed" in str(err.value)
    assert "t005 (6 converged, 2 not reached)" in str(err.value)
    assert "t007" not in str(err.value)


def test_files_on_different_amplitude_grids_are_refused(tmp_path):
    samples = design(8, 0)
    paths = write_campaign(tmp_path, samples, ALPHA, {"t002": dnnm_dataset([0, 0, 0], 2 * ALPHA)})
    with pytest.raises(ValueError, match="t002.*amplitude grid differs"):
        aggregate(samples, paths)


def test_a_truncated_dnnm_file_is_refused_naming_it(tmp_path):
    samples = design(8, 0)
    paths = write_campaign(tmp_path, samples, ALPHA)
    data = paths["t004"].read_bytes()
    paths["t004"].write_bytes(data[: len(data) // 3])
    with pytest.raises(ValueError, match=r"t004/dnnm\.nc: truncated or not a NetCDF file"):
        aggregate(samples, paths)


def test_flagged_truncations_name_each_ring_its_points_and_error(tmp_path):
    """A ring whose raises stopped at three amplitudes (two over budget, one failed) is named with its
    counts, amplitudes and largest estimated error; its points stay usable; unflagged rings are not named."""
    from ringdamper.campaign.dataset import flagged_truncations

    samples = design(10, 2)
    flagged = dnnm_dataset(samples.iloc[4, 1:4].to_numpy(float), ALPHA)
    flagged["truncation_flag"].values[:] = [0] * 5 + [1, 2, 1]
    flagged["truncation_error"].values[:] = [np.nan] * 5 + [2e-3, 0.04, 7e-3]
    ds = aggregate(samples, write_campaign(tmp_path, samples, ALPHA, {"t004": flagged}))
    assert ds.truncation_flag.attrs["units"] == "1" and "over its LU budget" in ds.truncation_flag.attrs["long_name"]
    lines = flagged_truncations(ds)
    assert len(lines) == 1 and lines[0].startswith("t004 (training): 3 point(s)")
    assert "(2 raise(s) over budget, 1 failed)" in lines[0] and "up to 0.04" in lines[0]
    assert ", ".join(f"{a:.3g}" for a in ALPHA[5:]) in lines[0]
    assert bool(usable_mask(ds).sel(geometry="t004").all())
    assert flagged_truncations(ds.drop_vars(["truncation_flag", "truncation_error"])) == []
