"""Backbones read at response levels: the interpolation against analytic backbones, the rule for
non-monotone predicted curves, and the grids of the exploration."""
import numpy as np
import pytest

from ringdamper.campaign.exploration import Backbones, at_levels, cube_grid, monotone, one_at_a_time, predicted_zeta_max

ALPHA = np.geomspace(1e-6, 3e-4, 30)


def test_levels_of_a_linear_backbone_are_exact():
    """x = c alpha, y = a + b x: piecewise-linear interpolation in x is exact."""
    c = np.array([2.0, 2.5, 3.0])
    x = ALPHA[:, None] * c
    y = np.stack([1.0 + 4e3 * x, -2e3 * x])
    levels = np.array([5e-6, 1e-4, 5e-4])
    out = at_levels(x, y, levels)
    assert out.shape == (2, 3, 3)
    np.testing.assert_allclose(out[0], 1.0 + 4e3 * levels[:, None] * np.ones(3), rtol=1e-12)
    np.testing.assert_allclose(out[1], -2e3 * levels[:, None] * np.ones(3), rtol=1e-12)


def test_levels_of_a_smooth_backbone_within_the_interpolation_bound():
    """y = sin(x / L) on a log-spaced grid: |error| <= h^2/8 max|y''| with h the local segment."""
    L = 1e-4
    x = (2.27 * ALPHA)[:, None]
    y = np.sin(x / L)
    levels = np.linspace(x[0, 0], x[-1, 0], 101)
    out = at_levels(x, y[None], levels)[0, :, 0]
    j = np.clip(np.searchsorted(x[:, 0], levels) - 1, 0, len(x) - 2)
    h = x[j + 1, 0] - x[j, 0]
    bound = h ** 2 / 8 / L ** 2 + 1e-12
    assert np.all(np.abs(out - np.sin(levels / L)) <= bound)
    assert np.max(np.abs(out - np.sin(levels / L))) > 1e-4  # the oracle is not trivially met


def test_unreached_levels_are_nan():
    x = np.linspace(1.0, 2.0, 5)[:, None] * [1.0, 3.0]  # spans [1, 2] and [3, 6]
    out = at_levels(x, x[None], [0.5, 1.5, 4.5])[0]
    assert np.isnan(out[0]).all()
    assert out[1, 0] == 1.5 and np.isnan(out[1, 1])
    assert np.isnan(out[2, 0]) and out[2, 1] == 4.5


def test_non_monotone_curves_use_the_documented_crossing():
    """x goes 0 -> 2 -> 1 -> 3: level 1.5 is crossed three times; 'first' takes the lowest alpha,
    'last' the highest."""
    x = np.array([0.0, 2.0, 1.0, 3.0])[:, None]
    y = np.array([10.0, 30.0, 50.0, 70.0])[None, :, None]
    assert not monotone(x)[0] and monotone(np.arange(4.0)[:, None])[0]
    assert at_levels(x, y, [1.5])[0, 0, 0] == pytest.approx(25.0)               # on [0, 2]
    assert at_levels(x, y, [1.5], crossing="last")[0, 0, 0] == pytest.approx(55.0)  # on [1, 3]
    with pytest.raises(ValueError, match="crossing"):
        at_levels(x, y, [1.5], crossing="middle")


def test_grids():
    g = cube_grid(5)
    assert g.shape == (125, 3) and g.min() == -1.0 and g.max() == 1.0
    assert np.all(g[:25, 0] == -1.0)  # kappa1 varies slowest
    box = cube_grid(3, [(0.9, 1.0), (-1.0, -0.9), (-1.0, -0.9)])
    assert box[:, 0].min() == 0.9 and box[:, 1].max() == -0.9
    s = one_at_a_time(1, 5)
    assert s[:, 1].tolist() == [-1.0, -0.5, 0.0, 0.5, 1.0] and not s[:, [0, 2]].any()


def test_zeta_max_up_to_a_response_level():
    """Two backbones whose damping peaks again at the top: the limit keeps the first peak."""
    q = np.array([1.0, 2.0, 3.0, 4.0])[:, None] * [1.0, 1.0]
    zeta = np.array([[0.1, 0.3, 0.2, 0.5], [0.1, 0.2, 0.4, 0.3]]).T
    bb = Backbones(amplitude=np.arange(4.0), mean={"q_res_z": q, "zeta": zeta}, std=None)
    value, j = predicted_zeta_max(bb)
    assert value.tolist() == [0.5, 0.4] and j.tolist() == [3, 2]
    value, j = predicted_zeta_max(bb, q_max=3.0)
    assert value.tolist() == [0.3, 0.4] and j.tolist() == [1, 2]
