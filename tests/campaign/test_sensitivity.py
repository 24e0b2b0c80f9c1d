"""Sobol indices (ringdamper.campaign.sensitivity) against analytic values."""

import numpy as np
import pytest

from ringdamper.campaign import sensitivity as SA

A, B = 7.0, 0.1
ISHIGAMI_BOUNDS = [[-np.pi, np.pi]] * 3


def ishigami(x):
    return np.sin(x[:, 0]) + A * np.sin(x[:, 1]) ** 2 + B * x[:, 2] ** 4 * np.sin(x[:, 0])


def ishigami_indices():
    """Analytic indices (Ishigami & Homma 1990; Sobol & Levitan 1999) for x ~ U[-π, π]^3:
    V = a²/8 + bπ⁴/5 + b²π⁸/18 + 1/2, V1 = (1 + bπ⁴/5)²/2, V2 = a²/8, V3 = 0,
    V13 = b²π⁸ (1/18 - 1/50), every other interaction 0."""
    v = A**2 / 8 + B * np.pi**4 / 5 + B**2 * np.pi**8 / 18 + 0.5
    v1, v2, v13 = 0.5 * (1 + B * np.pi**4 / 5) ** 2, A**2 / 8, B**2 * np.pi**8 * (1 / 18 - 1 / 50)
    return np.array([v1, v2, 0.0]) / v, np.array([v1 + v13, v2, v13]) / v


def test_ishigami_analytic_values():
    """The closed forms above give the published values (0.3139, 0.4424, 0; 0.5576, 0.4424, 0.2437)."""
    first, total = ishigami_indices()
    np.testing.assert_allclose(first, [0.3139, 0.4424, 0.0], atol=5e-5)
    np.testing.assert_allclose(total, [0.5576, 0.4424, 0.2437], atol=5e-5)


@pytest.mark.parametrize("estimator", sorted(SA.ESTIMATORS))
def test_ishigami_indices_lie_in_their_intervals(estimator):
    """N = 3·10⁴ base samples (1.5·10⁵ runs); 99 % intervals so that six indices all hold at once for most
    seeds (95 % would miss one in about a quarter of seeds); the intervals must be < 0.07 wide."""
    first, total = ishigami_indices()
    ds = SA.sobol_indices(ishigami, ISHIGAMI_BOUNDS, n_base=30_000, estimator=estimator, confidence_level=0.99,
                          output_names=["y"])
    assert ds.first_order.dims == ("output", "parameter")
    assert np.all((ds.first_order_lower.values[0] <= first) & (first <= ds.first_order_upper.values[0]))
    assert np.all((ds.total_order_lower.values[0] <= total) & (total <= ds.total_order_upper.values[0]))
    assert np.max(ds.first_order_upper.values - ds.first_order_lower.values) < 0.07
    assert np.max(ds.total_order_upper.values - ds.total_order_lower.values) < 0.07


def test_seeded_runs_are_identical():
    one = SA.sobol_indices(ishigami, ISHIGAMI_BOUNDS, n_base=1000, interval="bootstrap", bootstrap_size=50, seed=3)
    two = SA.sobol_indices(ishigami, ISHIGAMI_BOUNDS, n_base=1000, interval="bootstrap", bootstrap_size=50, seed=3)
    assert all(np.array_equal(one[v].values, two[v].values, equal_nan=True) for v in one.data_vars)


def test_pce_cross_check_matches_analytic():
    first, total = ishigami_indices()
    ds = SA.sobol_indices_pce(ishigami, ISHIGAMI_BOUNDS, degree=8, n_train=500)
    np.testing.assert_allclose(ds.first_order.values[0], first, atol=0.01)
    np.testing.assert_allclose(ds.total_order.values[0], total, atol=0.01)
    assert np.all(np.isnan(ds.first_order_lower.values))


def test_function_of_x1_only_several_outputs():
    """Two outputs of x1 alone (one nonlinear, one with a large offset) and one constant output:
    S1 = T1 = 1, the others 0 (T₂ = T₃ = 0 exactly since y_E = y_A there, the rest to the Monte Carlo
    noise 1/√N, tolerance 4/√N), the constant one NaN."""
    def f(x):
        return np.column_stack([np.exp(x[:, 0]), 1e3 + np.sin(3 * x[:, 0]), np.full(len(x), 2.0)])

    n = 5000
    ds = SA.sobol_indices(f, [[0.0, 1.0], [-1.0, 1.0], [-1.0, 1.0]], n_base=n, output_names=["a", "b", "c"])
    for name in ("a", "b"):
        row = ds.sel(output=name)
        assert row.first_order.values[0] == pytest.approx(1.0, abs=4.0 / np.sqrt(n))
        assert row.total_order.values[0] == pytest.approx(1.0, abs=4.0 / np.sqrt(n))
        np.testing.assert_allclose(row.total_order.values[1:], 0.0, atol=1e-12)
        np.testing.assert_allclose(row.first_order.values[1:], 0.0, atol=4.0 / np.sqrt(n))
    assert np.all(np.isnan(ds.sel(output="c").first_order.values))
    pce = SA.sobol_indices_pce(f, [[0.0, 1.0], [-1.0, 1.0], [-1.0, 1.0]], degree=6, n_train=200)
    np.testing.assert_allclose(pce.first_order.values[:2], [[1, 0, 0]] * 2, atol=1e-6)
    np.testing.assert_allclose(pce.total_order.values[:2], [[1, 0, 0]] * 2, atol=1e-6)


@pytest.mark.parametrize("bounds, message", [
    ([[0.0, 1.0], [1.0, 1.0], [0.0, 1.0]], r"bounds\[1\]"),
    ([[0.0, np.nan], [0.0, 1.0], [0.0, 1.0]], r"bounds\[0\]"),
    ([0.0, 1.0], "shape"),
])
def test_bad_bounds_are_named(bounds, message):
    with pytest.raises(ValueError, match=message):
        SA.sobol_indices(ishigami, bounds, n_base=100)
    with pytest.raises(ValueError, match=message):
        SA.sobol_indices_pce(ishigami, bounds)


def test_bad_estimator_and_nonfinite_output():
    with pytest.raises(ValueError, match="estimator"):
        SA.sobol_indices(ishigami, ISHIGAMI_BOUNDS, n_base=100, estimator="sobol")
    with pytest.raises(ValueError, match=r"non-finite values for outputs \['y0'\]"):
        SA.sobol_indices(lambda x: np.where(x[:, 0] > 0, 1.0, np.nan), ISHIGAMI_BOUNDS, n_base=100)
