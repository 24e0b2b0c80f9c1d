"""Ordinary Kriging (ringdamper.campaign.kriging) against oracles: a known smooth function, OpenTURNS'
own GaussianProcessRegression, brute-force leave-one-out, degenerate and invalid data."""

import numpy as np
import openturns as ot
import pytest
import xarray as xr
from scipy.stats import qmc

from ringdamper.campaign import kriging as K
from ringdamper.io import read_netcdf, write_netcdf

FAST = {"n_starts": 4}


def smooth(x):
    """Test function on [-1, 1]^3: smooth, anisotropic, with an interaction."""
    return np.sin(2.0 * x[:, 0]) + 0.5 * np.cos(3.0 * x[:, 1]) * x[:, 2] + 0.3 * x[:, 2] ** 2


def lhs(n, seed):
    return 2.0 * qmc.LatinHypercube(d=3, rng=np.random.default_rng(seed)).random(n) - 1.0


@pytest.fixture(scope="module")
def training():
    x = lhs(100, 1)
    return x, smooth(x)


@pytest.fixture(scope="module")
def fitted(training):
    x, y = training
    model, _ = K.fit_model(x, y, FAST)
    return model


@pytest.fixture(scope="module")
def test_points():
    x = np.random.default_rng(5).uniform(-1.0, 1.0, (1000, 3))
    return x, smooth(x)


def campaign_dataset(n_geometries=40, seed=3):
    """Synthetic dataset.nc: dims (geometry, amplitude), the four outputs depending on κ and α."""
    kappa = lhs(n_geometries, seed)
    alpha = np.array([1e-6, 1e-5, 1e-4])
    base = smooth(kappa)[:, None]
    dims = ("geometry", "amplitude")
    outputs = {
        "q_res_z": (1e-4 * (1.2 + 0.3 * base) * alpha / alpha[-1], "m", "resonant amplitude"),
        "omega0": (1.0 + 0.01 * kappa[:, :1] - 1e-3 * base * np.log10(alpha / alpha[0]), "1", "normalised frequency"),
        "zeta": (np.zeros((n_geometries, 3)), "1", "damping ratio"),
        "gamma": ((2.0 + base) * alpha / alpha[0], "N", "forcing level"),
    }
    names = [f"t{i:03d}" for i in range(n_geometries)]
    coords = {"geometry": ("geometry", names, {"units": "1", "long_name": "geometry id"}),
              "amplitude": ("amplitude", alpha, {"units": "kg0.5 m", "long_name": "modal amplitude"})}
    for k in range(3):
        coords[f"kappa{k + 1}"] = ("geometry", kappa[:, k], {"units": "1", "long_name": f"kappa{k + 1}"})
    ds = xr.Dataset({name: (dims, values, {"units": units, "long_name": long_name})
                     for name, (values, units, long_name) in outputs.items()}, coords=coords)
    return ds


def ot_prediction(x, y, settings, points):
    """Mean and variance of OpenTURNS' GaussianProcessRegression fitted with the same settings."""
    algo = ot.GaussianProcessRegression(K.fit_ot(x, y, settings))
    algo.run()
    result = algo.getResult()
    mean = np.asarray(result.getMetaModel()(points)).ravel()
    var = np.asarray(ot.GaussianProcessConditionalCovariance(result).getConditionalMarginalVariance(points)).ravel()
    return mean, var


def test_interpolates_training_data_without_nugget(training, fitted):
    x, y = training
    mean, std = fitted.predict(x)
    assert np.max(np.abs(mean - y)) <= 1e-8 * np.ptp(y)
    assert np.max(std) <= 1e-4 * fitted.sigma  # no uncertainty left at the data


def test_recovers_smooth_function(fitted, test_points):
    x, y = test_points
    mean, _ = fitted.predict(x, with_std=False)
    r2 = 1.0 - np.sum((mean - y) ** 2) / np.sum((y - y.mean()) ** 2)
    assert r2 > 0.999


def test_predictive_std_covers_the_error(fitted, test_points):
    """|error| < 2σ at a rate near the Gaussian 95.4 %: accepted in [0.85, 1.0] (ML σ is an estimate)."""
    x, y = test_points
    mean, std = fitted.predict(x)
    rate = np.mean(np.abs(mean - y) < 2.0 * std)
    assert 0.85 <= rate <= 1.0


def bumpy(x):
    """A well-conditioned case (short correlation lengths): cond(R) ~ 1e5."""
    return np.exp(-3.0 * np.sum((x - 0.3) ** 2, axis=1)) + 0.3 * np.tanh(4.0 * x[:, 1])


@pytest.mark.parametrize("function", [smooth, bumpy])
def test_analytic_loo_equals_brute_force(training, function):
    """Dubrule's formula vs removing each point and predicting with the same θ, σ, ν (β re-estimated by
    GLS on the N - 1 others): equal to 1e-8 of the largest residual (measured: 1e-10 with cond(R) ~ 6e8
    on the smooth function, 2e-13 with cond(R) ~ 8e4 on the bumpy one)."""
    x = training[0]
    model, _ = K.fit_model(x, function(x), FAST)
    e = model.loo_residuals()
    brute = np.empty_like(e)
    for i in range(len(e)):
        keep = np.arange(len(e)) != i
        sub = K.GPModel(model.kernel, model.scale, model.sigma, model.nugget, 0.0, model.x[keep], model.y[keep])
        sub = K.GPModel(model.kernel, model.scale, model.sigma, model.nugget, sub.gls_beta(), sub.x, sub.y)
        brute[i] = model.y[i] - sub.predict(model.x[i:i + 1], with_std=False)[0][0]
    assert np.max(np.abs(e - brute)) <= 1e-8 * np.max(np.abs(e))
    assert 0.99 < K.q2(model.y, e) <= 1.0


@pytest.mark.parametrize("function, settings", [
    (smooth, FAST),
    (bumpy, {**FAST, "kernel": "squared_exponential"}),
    (smooth, {**FAST, "nugget": [1e-6, 1e-2]}),
])
def test_stored_dataset_prediction_equals_openturns(tmp_path, function, settings):
    """Fit through fit_campaign, write/read kriging.nc, predict in numpy; OpenTURNS fitted on the same
    data with the same settings (deterministic) must give the same mean and variance, to 1e-8 of the
    data spread and of σ² (measured: 1e-11 and 1e-9 with cond(R) ~ 5e7, 1e-14 when well conditioned);
    the calibrated standard deviation is the ML one times √ψ, ψ the stored variance factor."""
    ds = campaign_dataset(60)
    kappa = np.column_stack([ds[f"kappa{k}"].values for k in (1, 2, 3)])
    ds["gamma"] = ds["gamma"] * 0 + function(kappa)[:, None]
    settings = {**settings, "transform": {"gamma": "identity"}}  # OpenTURNS models y itself
    path = tmp_path / "kriging.nc"
    write_netcdf(K.fit_campaign(ds, outputs=("gamma",), settings=settings), path)
    stored = read_netcdf(path)
    points = np.random.default_rng(11).uniform(-1, 1, (300, 3))
    pred = K.predict(stored, points)
    surrogate = K.KrigingSurrogate(stored)
    (_, _, model), = [g for g in surrogate.groups.values() for g in g if g[1] == 0]
    mean_ot, var_ot = ot_prediction(kappa, ds["gamma"].values[:, 0], settings, points)
    mean, std = pred["gamma"].values[0], pred["gamma_std"].values[0]
    assert np.max(np.abs(mean - mean_ot)) <= 1e-8 * np.ptp(model.y)
    psi = float(stored["gamma_variance_factor"].values[0])
    assert model.variance_factor == psi and psi > 0
    assert np.max(np.abs(std**2 / psi - var_ot)) <= 1e-8 * model.sigma**2
    raw = K.KrigingSurrogate(stored, calibrated=False).predict(points)["gamma_std"].values[0]
    np.testing.assert_allclose(std, np.sqrt(psi) * raw, rtol=1e-12)
    assert pred["gamma"].attrs["units"] == "N"


def test_openturns_cross_check_skips_midpoints_on_training_inputs(caplog):
    """The midpoint of the first two rings, (-1,-1,-1) and (1,1,1), is the third, (0,0,0): there OpenTURNS
    returns the noisy observation (its mean differs from ours by 1.5e-2 of the data spread here, of the
    order of ν), which is no sign of ill-conditioning; the cross-check leaves such points out."""
    x = np.vstack([[-1.0, -1.0, -1.0], [1.0, 1.0, 1.0], [0.0, 0.0, 0.0], lhs(40, 6)])
    y = smooth(x) + 0.05 * np.random.default_rng(7).standard_normal(len(x))
    with caplog.at_level("WARNING", logger="ringdamper.campaign.kriging"):
        model, _ = K.fit_model(x, y, {**FAST, "nugget": 0.05})
    assert model.nugget == 0.05
    assert not [r for r in caplog.records if "differ" in r.getMessage()]


def test_estimated_nugget_smooths_noise():
    """Noisy data (σ_noise = 2 % of the spread): the profiled nugget is large and the prediction is
    closer to the truth than the data are; a fixed tiny nugget interpolates the noise instead."""
    x = lhs(100, 2)
    noise = 0.02 * np.ptp(smooth(x)) * np.random.default_rng(4).standard_normal(100)
    y = smooth(x) + noise
    model, _ = K.fit_model(x, y, {**FAST, "nugget": [1e-8, 1e-1]})
    assert model.nugget >= 1e-4
    mean, _ = model.predict(x, with_std=False)
    assert np.sqrt(np.mean((mean - smooth(x)) ** 2)) < 0.7 * np.sqrt(np.mean(noise**2))


def test_campaign_dataset_layout_and_degenerate_outputs():
    ds = campaign_dataset()
    out = K.fit_campaign(ds, settings=FAST)
    assert out["scale"].dims == ("output", "amplitude", "parameter")
    zeta = list(out["output"].values).index("zeta")
    assert np.all(out["status"].values[zeta] == K.STATUS_CONSTANT)  # ζ ≡ 0 at every amplitude
    assert np.all(out["status"].values[[i for i in range(4) if i != zeta]] == K.STATUS_GP)
    pred = K.predict(out, lhs(50, 9))
    np.testing.assert_array_equal(pred["zeta"].values, 0.0)
    np.testing.assert_array_equal(pred["zeta_std"].values, 0.0)
    # round-off-sized scatter is still constant data: no OpenTURNS fit, no crash
    model, _ = K.fit_model(lhs(20, 1), 0.3 + 1e-17 * np.arange(20), FAST)
    assert model.is_constant and model.beta == pytest.approx(0.3)


def test_models_do_not_depend_on_the_number_of_worker_processes():
    ds = campaign_dataset()
    serial = K.fit_campaign(ds, settings=FAST)
    pooled = K.fit_campaign(ds, settings=FAST, workers=2)
    for name, var in serial.data_vars.items():
        if var.dtype.kind == "f":
            np.testing.assert_array_equal(var.values, pooled[name].values, err_msg=name)
        else:
            assert (var.values == pooled[name].values).all(), name


def test_a_stored_fit_is_recognised_only_on_its_own_training_data_and_settings(tmp_path):
    """fitted_on (the kriging rule takes the adaptive design's stopping round's models with it): true for a
    fit read back from kriging.nc, whose every model equals a fit made again; false once one training value,
    the training mask or a setting differs."""
    ds = campaign_dataset()
    mask = np.ones((ds.sizes["geometry"], ds.sizes["amplitude"]), bool)
    mask[3, 2] = False
    write_netcdf(K.fit_campaign(ds, mask=mask, settings=FAST), tmp_path / "kriging.nc")
    stored = read_netcdf(tmp_path / "kriging.nc")
    assert K.fitted_on(stored, ds, mask=mask, settings=FAST)
    again = K.fit_campaign(ds, mask=mask, settings=FAST)
    for name, var in again.data_vars.items():
        np.testing.assert_array_equal(stored[name].values, var.values, err_msg=name)
    changed = ds.copy(deep=True)
    changed["gamma"][7, 1] *= 1.0 + 1e-15
    assert not K.fitted_on(stored, changed, mask=mask, settings=FAST)
    assert not K.fitted_on(stored, ds, settings=FAST)
    assert not K.fitted_on(stored, ds, mask=mask, settings={**FAST, "n_starts": 3})
    moved = ds.assign_coords(kappa1=ds.kappa1 + 5e-11 * np.sign(ds.kappa1))
    assert not K.fitted_on(stored, moved, mask=mask, settings=FAST)
    assert K.fitted_on(stored, moved, mask=mask, settings=FAST, kappa_tolerance=1e-9)


def test_nan_training_value_is_rejected_with_its_name():
    ds = campaign_dataset()
    ds["zeta"][4, 1] = np.nan
    with pytest.raises(ValueError, match=r"zeta at amplitude\[1\]"):
        K.fit_campaign(ds, outputs=("zeta",), settings=FAST)
    mask = np.ones((ds.sizes["geometry"], ds.sizes["amplitude"]), bool)
    mask[4, 1] = False
    out = K.fit_campaign(ds, outputs=("zeta",), mask=mask, settings=FAST)
    assert out["n_training"].values[0].tolist() == [40, 39, 40]
    assert np.isnan(out["zeta"].values[1, 4])
    # a per-geometry mask drops the geometry from the file altogether
    out = K.fit_campaign(ds, outputs=("zeta",), mask=np.arange(ds.sizes["geometry"]) != 4, settings=FAST)
    assert out.sizes["geometry"] == 39 and "t004" not in out["geometry"].values


def test_too_few_training_points_leave_the_model_unfitted():
    ds = campaign_dataset()
    mask = np.zeros((ds.sizes["geometry"], ds.sizes["amplitude"]), bool)
    mask[:, :2] = True
    mask[:5, 2] = True
    out = K.fit_campaign(ds, outputs=("gamma",), mask=mask, settings=FAST)
    assert out["status"].values[0].tolist() == [K.STATUS_GP, K.STATUS_GP, K.STATUS_UNFITTED]
    pred = K.predict(out, lhs(10, 2))
    assert np.all(np.isnan(pred["gamma"].values[2])) and np.all(np.isfinite(pred["gamma"].values[:2]))


@pytest.mark.parametrize("settings, message", [
    ({"kernel": "cubic"}, "surrogate.kernel"),
    ({"scale_bounds": [5.0, 1.0]}, "surrogate.scale_bounds"),
    ({"nugget": -1.0}, "surrogate.nugget"),
    ({"n_starts": 0}, "surrogate.n_starts"),
    ({"starts": 3}, "unknown keys"),
])
def test_bad_settings_are_named(settings, message):
    with pytest.raises(ValueError, match=message):
        K.check_settings(settings)


def test_fit_does_not_depend_on_the_output_unit():
    """|q_res,z| is ~1e-5 m in SI: scaling the data by 1e-5 scales the predictions and leaves θ
    unchanged, to the optimiser's tolerance (measured 1e-5 relative)."""
    x = lhs(30, 2)
    y = np.exp(-np.sum((x - 0.2) ** 2, axis=1))
    one, _ = K.fit_model(x, y, FAST)
    small, _ = K.fit_model(x, 1e-5 * y, FAST)
    points = lhs(100, 8)
    (m1, s1), (m2, s2) = one.predict(points), small.predict(points)
    np.testing.assert_allclose(small.scale, one.scale, rtol=1e-3)
    np.testing.assert_allclose(m2, 1e-5 * m1, rtol=0, atol=1e-3 * 1e-5 * np.ptp(y))
    np.testing.assert_allclose(s2, 1e-5 * s1, rtol=0, atol=1e-3 * 1e-5 * one.sigma)


def test_ml_amplitude_is_the_closed_form_estimate(training):
    """σ̂² = (y − β̂1)ᵀR⁻¹(y − β̂1)/(N − 1) at OpenTURNS' optimum θ equals its own amplitude (the
    closed form that replaces a non-ML amplitude OpenTURNS sometimes returns)."""
    x, y = training
    result = K.fit_ot(x, y, FAST)
    cm = result.getCovarianceModel()
    model = K.GPModel("matern52", np.array(cm.getScale()), 1.0, cm.getNuggetFactor(),
                            result.getTrendCoefficients()[0], x, y)
    assert model.ml_sigma() == pytest.approx(cm.getAmplitude()[0], rel=1e-8)


@pytest.mark.parametrize("kernel", K.KERNELS)
def test_likelihood_gradient_matches_finite_differences(training, kernel):
    """The analytic gradient the polish climbs (log θ, log ν) equals central differences of ℓ to 1e-6 of
    its norm, and ℓ equals the model's own (OpenTURNS') reduced log-likelihood."""
    from ringdamper.campaign.kriging.gp import GPModel, log_likelihood_gradient

    x, y = training[0][:40], training[1][:40]
    p = np.log([0.7, 1.3, 2.1, 1e-4])

    def ell(q):
        return log_likelihood_gradient(kernel, x, y, np.exp(q[:3]), float(np.exp(q[3])))[0]

    value, grad = log_likelihood_gradient(kernel, x, y, np.exp(p[:3]), float(np.exp(p[3])))
    h = 1e-5
    numeric = np.array([(ell(p + h * e) - ell(p - h * e)) / (2 * h) for e in np.eye(4)])
    assert np.max(np.abs(grad - numeric)) <= 1e-6 * np.linalg.norm(grad)
    assert value == pytest.approx(GPModel(kernel, np.exp(p[:3]), 1.0, float(np.exp(p[3])), 0.0, x, y).log_likelihood(),
                                  rel=1e-12)
