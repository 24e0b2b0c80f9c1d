"""Validation metrics against hand-computed values, and Q^2 from the leave-one-out residuals."""
import numpy as np
import pytest

from ringdamper.campaign.kriging import fit_campaign
from ringdamper.campaign.validation import loo_pairs, metrics, r2

from .synthetic import design


def test_metrics_against_hand_values():
    # residuals 0.1, -0.1, 0.2, -0.2: SS_res = 0.10; SS_tot = 2.25 + 0.25 + 0.25 + 2.25 = 5 about 2.5,
    # 4 x 0.25 = 1 about the group means 1.5 and 3.5; |e| <= 2 sigma for samples 0 and 2 only
    y = np.array([1.0, 2.0, 3.0, 4.0])
    y_hat = np.array([1.1, 1.9, 3.2, 3.8])
    std = np.array([0.1, 0.01, 0.2, 0.05])
    m = metrics(y, y_hat, y_hat - 2 * std, y_hat + 2 * std, group=[0, 0, 1, 1])
    assert m["r2"] == pytest.approx(1 - 0.10 / 5, abs=1e-12)
    assert m["r2_within"] == pytest.approx(1 - 0.10 / 1, abs=1e-12)
    assert m["rmse"] == pytest.approx(np.sqrt(0.10 / 4), abs=1e-12)
    assert m["max_error"] == pytest.approx(0.2, abs=1e-12)
    assert m["coverage"] == 0.5 and m["n_points"] == 4


def test_q2_from_kriging_nc_matches_the_per_model_q2():
    """One amplitude: the pooled Q^2 of loo_pairs is the model's own Q^2 (stored by the fit)."""
    import xarray as xr

    samples = design(20, 0, seed=3)
    k = samples[["kappa1", "kappa2", "kappa3"]].to_numpy()
    y = np.sin(2 * k[:, 0]) + 0.5 * k[:, 1] * k[:, 2]
    ds = xr.Dataset({"y": (("geometry", "amplitude"), y[:, None], {"units": "1", "long_name": "y"})},
                    coords={"kappa1": ("geometry", k[:, 0]), "kappa2": ("geometry", k[:, 1]),
                            "kappa3": ("geometry", k[:, 2]), "amplitude": ("amplitude", [1.0])})
    fit = fit_campaign(ds, outputs=("y",), settings={"n_starts": 2, "min_training": 5})
    ly, lhat, group = loo_pairs(fit, "y")
    assert ly.size == 20 and np.all(group == 0)
    assert r2(ly, lhat) == pytest.approx(float(fit.q2.values[0, 0]), abs=1e-12)
    assert 0.5 < r2(ly, lhat) < 1.0
