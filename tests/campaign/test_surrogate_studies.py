"""Studies on the Kriging surrogates of a synthetic campaign with analytic backbones
(tests/campaign/synthetic.py): validation, the level function, the optimum and the Sobol indices."""
import numpy as np
import pytest

from ringdamper.campaign.dataset import aggregate, usable_mask
from ringdamper.campaign.exploration import (
    ENVELOPE_OUTPUTS,
    at_levels,
    cube_grid,
    explore_grid,
    find_optimum,
    forcing_of,
    level_function,
    response_axis,
    summary,
)
from ringdamper.campaign.kriging import KrigingSurrogate, fit_campaign
from ringdamper.campaign.sobol_levels import pce_cross_check, sobol_study
from ringdamper.campaign.validation import validate
from ringdamper.io import check_contract

from .synthetic import KAPPA_STAR, backbone, design, write_campaign

ALPHA = np.geomspace(1e-6, 3e-4, 12)
LEVELS = [5e-5, 1e-4, 2e-4, 4e-4]


@pytest.fixture(scope="module")
def campaign(tmp_path_factory):
    samples = design(60, 10, seed=5)
    ds = aggregate(samples, write_campaign(tmp_path_factory.mktemp("synthetic"), samples, ALPHA))
    mask = usable_mask(ds)
    train = (ds.split == "training").values
    fit = fit_campaign(ds.isel(geometry=train), mask=mask.isel(geometry=train),
                       settings={"n_starts": 3, "min_training": 10})
    return ds, mask, fit, KrigingSurrogate(fit)


def test_validation_dataset(campaign):
    ds, mask, fit, surrogate = campaign
    val = validate(fit, surrogate, ds, mask)
    check_contract(val)
    assert list(val.output.values) == ["q_res_z", "omega0", "zeta", "gamma"]
    assert val.sizes["geometry"] == 10 and np.all(val.n_points == 10 * ALPHA.size)
    assert np.all(val.r2 > 0.99) and np.all(val.q2 > 0.99)
    assert np.all(val.r2_within <= val.r2 + 1e-12)
    assert np.all((val.coverage >= 0) & (val.coverage <= 1))
    assert val.zeta_predicted.attrs["units"] == "1" and val.gamma_std.attrs["units"] == "N"


def test_level_function_columns_follow_outputs_then_levels(campaign):
    """f(kappa) against the analytic backbone read at the same levels (the Kriging error only)."""
    _, _, _, surrogate = campaign
    X = np.array([[0.3, -0.2, 0.5], [-0.7, 0.6, -0.1]])
    got = level_function(surrogate, LEVELS)(X)
    assert got.shape == (2, len(ENVELOPE_OUTPUTS) * len(LEVELS))
    for p, k in enumerate(X):
        b = backbone(k, ALPHA)
        ref = at_levels(b["q_res_z"][:, None], np.stack([b[o] for o in ENVELOPE_OUTPUTS])[:, :, None], LEVELS)
        ranges = np.array([np.ptp(b[o]) for o in ENVELOPE_OUTPUTS])
        err = np.abs(got[p].reshape(3, -1) - ref[:, :, 0]) / ranges[:, None]
        assert err.max() < 0.01, err
    with pytest.raises(ValueError, match=r"level\(s\) \[0.002\] m not reached"):
        level_function(surrogate, [2e-3])(X)


def test_optimum_is_the_known_maximiser(campaign):
    """zeta_peak is largest at KAPPA_STAR (an interior point off the grid nodes)."""
    ds, mask, _, surrogate = campaign
    levels = response_axis(ds, mask, 50)
    forcing = forcing_of(surrogate, np.zeros(3), 1e-4)
    grid = explore_grid(surrogate, cube_grid(11), levels, forcing, chunk=500)
    assert grid.n_non_monotone == 0
    assert np.all(grid.lower["zeta"] <= grid.upper["zeta"])
    opt = find_optimum(surrogate, grid, forcing, 11)
    assert np.linalg.norm(opt["kappa"] - KAPPA_STAR) < 0.05
    assert np.linalg.norm(opt["kappa"] - KAPPA_STAR) < np.linalg.norm(opt["grid_kappa"] - KAPPA_STAR)
    exact = backbone(KAPPA_STAR, ALPHA)["zeta"].max()
    assert grid.zeta_max.max() == pytest.approx(exact, rel=0.02)
    # second view: at the forcing that drives the default ring to 0.1 mm, the best ring responds less
    # (gamma(alpha) of this model falls past the zeta peak: the largest balancing amplitude counts)
    default = summary(surrogate, np.zeros(3), forcing)["q_res_z_at_forcing"]
    assert default > 1e-4
    assert opt["q_min"] <= np.nanmin(grid.q_at_forcing) < default


def test_sobol_indices_by_level(campaign):
    """omega0 at a level depends on kappa1 only (q = c(kappa1) alpha): S1 = T1 = 1, T2 = T3 = 0."""
    _, _, _, surrogate = campaign
    settings = {"n_base": 2000, "estimator": "martinez", "seed": 3, "confidence_level": 0.95,
                "pce_degree": 4, "pce_samples": 200}
    mc = sobol_study(surrogate, LEVELS, [[-1, 1]] * 3, settings)
    check_contract(mc)
    assert dict(mc.sizes) == {"output": 3, "parameter": 3, "level": 4}
    for kind in ("first_order", "total_order"):
        assert np.all(mc[f"{kind}_lower"] <= mc[kind]) and np.all(mc[kind] <= mc[f"{kind}_upper"])
    w = mc.sel(output="omega0")
    assert np.all(w.first_order.sel(parameter="kappa1") > 0.97)
    assert np.all(w.total_order.sel(parameter=["kappa2", "kappa3"]) < 0.02)
    checked = pce_cross_check(surrogate, LEVELS, [[-1, 1]] * 3, settings, mc)
    assert checked.first_order_pce.dims == ("output", "parameter", "level")
    assert checked.attrs["first_order_pce_max_abs_difference"] < 0.05
    local = sobol_study(surrogate, LEVELS, [[0.9, 1.0], [-1.0, -0.9], [-1.0, -0.9]], settings)
    np.testing.assert_array_equal(local.parameter_lower, [0.9, -1.0, -1.0])
