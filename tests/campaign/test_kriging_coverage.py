"""Calibrated Kriging variance (ringdamper.campaign.kriging.gp, *variance calibration*) against oracles.

* Brute force: the factor ψ from the analytic leave-one-out formulas equals the one from N refits
  without each point (fixed hyperparameters).
* Known truth: on sample paths of a Matérn 5/2 process (unit variance, θ = 0.8), 40 LHS training
  points, 500 uniform test points per path and 6 paths (3000 points in all), the ±2σ band of the
  calibrated predictor covers the true error within 3 points of the nominal 95.45 % (the plain
  ML band covers 91 % on the same data: the estimated hyperparameters make it overconfident).
* A kriging.nc written before the calibration is refused, naming the missing variable.
"""
import numpy as np
import pytest
from scipy.stats import qmc

from ringdamper.campaign import kriging as K
from ringdamper.campaign.kriging import gp

from .test_kriging import campaign_dataset

SCALE = 0.8


def gp_path(n, m, seed):
    """Training (n, LHS) and test (m, uniform) inputs in [-1, 1]^3 and one joint sample path."""
    rng = np.random.default_rng(seed)
    x = np.vstack([2 * qmc.LatinHypercube(d=3, rng=rng).random(n) - 1, rng.uniform(-1, 1, (m, 3))])
    R = gp.correlation("matern52", gp._scaled_d2(gp._squared_differences(x, x), np.full(3, SCALE)))
    y = np.linalg.cholesky(R + 1e-10 * np.eye(len(x))) @ rng.standard_normal(len(x))
    return x[:n], y[:n], x[n:], y[n:]


def test_variance_factor_against_brute_force_leave_one_out():
    x, y, _, _ = gp_path(25, 0, 11)
    model, _ = K.fit_model(x, y, {"n_starts": 4})
    t = []
    for i in range(len(y)):
        keep = np.arange(len(y)) != i
        sub = K.GPModel(model.kernel, model.scale, model.sigma, model.nugget, 0.0, x[keep], y[keep])
        sub = K.GPModel(model.kernel, model.scale, model.sigma, model.nugget, sub.gls_beta(),
                        x[keep], y[keep])
        mean, std = sub.predict(x[i:i + 1])
        t.append(abs(y[i] - mean[0]) / std[0])
    k = int(np.ceil((len(y) + 1) * K.BAND_PROBABILITY))
    expected = (np.sort(t)[min(k, len(y)) - 1] / 2.0) ** 2
    assert model.loo_variance_factor() == pytest.approx(expected, rel=1e-8)


def test_calibrated_band_covers_gaussian_process_paths_at_the_nominal_rate():
    hits_ml, hits_cal = [], []
    for seed in range(6):
        x, y, xt, yt = gp_path(40, 500, seed)
        model, _ = K.fit_model(x, y, {"n_starts": 4})
        mean, std = model.predict(xt)
        err = np.abs(mean - yt)
        hits_ml.append(err <= 2 * std)
        hits_cal.append(err <= 2 * std * np.sqrt(model.loo_variance_factor()))
    ml, cal = np.mean(hits_ml), np.mean(hits_cal)
    assert cal == pytest.approx(K.BAND_PROBABILITY, abs=0.03)
    assert ml < K.BAND_PROBABILITY - 0.03


def test_a_kriging_file_without_variance_factors_is_refused_by_name():
    fit = K.fit_campaign(campaign_dataset(20), outputs=("gamma",), settings={"n_starts": 2})
    with pytest.raises(ValueError, match="gamma_variance_factor"):
        K.KrigingSurrogate(fit.drop_vars("gamma_variance_factor"))
    assert K.KrigingSurrogate(fit.drop_vars("gamma_variance_factor"), calibrated=False).outputs == ["gamma"]
