"""Backbone summaries, the surrogate-vs-computed table at the optimum, the paper comparison and the
HTML tables of the report, on synthetic backbones whose answers are known."""
import numpy as np
import pandas as pd
import pytest
import xarray as xr

from ringdamper.campaign import paper
from ringdamper.campaign.optimum_check import surrogate_vs_computed
from ringdamper.campaign.paper import paper_comparison
from ringdamper.campaign.report_tables import html_table
from ringdamper.campaign.summary import backbone_summary, dnnm_summary, grid_zeta_max, log_q_zeta_max
from ringdamper.io import variable


def backbone(zeta_max, q_peak, omega0_low, omega0_peak, status=None, n=30):
    """dnnm-like dataset: |q| log-spaced, ζ a bump of height ``zeta_max`` at ``q_peak`` (a grid
    point), ω0 falling linearly in log|q| from ``omega0_low`` to ``omega0_peak`` at the peak."""
    q = np.geomspace(q_peak / 30, q_peak * 5, n)
    q[np.argmin(abs(np.log(q / q_peak)))] = q_peak
    x = np.log(q / q_peak)
    zeta = zeta_max * np.exp(-x ** 2)
    omega0 = omega0_low - (omega0_low - omega0_peak) * np.clip((x + 3) / 3, 0, 1)
    status = np.zeros(n, int) if status is None else status
    return xr.Dataset({"q_res_z": variable("amplitude", q, "m", "q"),
                       "omega0": variable("amplitude", omega0, "1", "w0"),
                       "zeta": variable("amplitude", zeta, "1", "zeta"),
                       "gamma": variable("amplitude", 10 * zeta * q / q_peak, "N", "gamma"),
                       "status": variable("amplitude", status, "1", "status")},
                      coords={"amplitude": variable("amplitude", q / 100, "kg0.5 m", "alpha")},
                      attrs={"kappa": np.array([1.0, -1.0, -1.0])})


def test_backbone_summary_finds_the_damping_peak_and_skips_unusable_points():
    ds = backbone(2e-3, 1.5e-4, 2.195, 2.187)
    s = dnnm_summary(ds)
    assert s["zeta_max"] == pytest.approx(2e-3) and s["q_at_zeta_max"] == pytest.approx(1.5e-4)
    assert s["omega0_at_zeta_max"] == pytest.approx(2.187, abs=1e-12)
    assert s["omega0_low"] == pytest.approx(ds.omega0.values[0])
    status = np.zeros(30, int)
    status[np.argmax(ds.zeta.values)] = 1                  # the peak point failed: not the maximum
    status[-3:] = 2
    s2 = backbone_summary(ds.q_res_z, ds.omega0, ds.zeta, status)
    assert s2["zeta_max"] < 2e-3 and s2["q_high"] == pytest.approx(ds.q_res_z.values[-4])
    with pytest.raises(ValueError, match="no usable point"):
        backbone_summary(ds.q_res_z, ds.omega0, ds.zeta, np.ones(30, int))


def test_zeta_max_read_on_the_grid_and_interpolated_in_log_q():
    """ζ a parabola in ln q peaking between two nodes: the grid reading is the higher node, the
    log-q reading the vertex; at an end of the searched range both are the grid value."""
    x = np.linspace(-1, 1, 9)
    q, zeta = np.exp(x), 2.0 - 3.0 * (x - 0.13) ** 2
    q_star, z_star = log_q_zeta_max(q, zeta)
    assert np.log(q_star) == pytest.approx(0.13, abs=1e-12) and z_star == pytest.approx(2.0, abs=1e-12)
    value, j = grid_zeta_max(q, zeta)
    assert j == 5 and value == zeta[5]                 # x = 0.25 lies nearer the vertex than x = 0
    assert log_q_zeta_max(q, zeta, q_max=np.exp(0.1)) == pytest.approx((1.0, zeta[4]))
    assert grid_zeta_max(q, zeta, q_max=np.exp(0.1))[1] == 4
    assert log_q_zeta_max(q, x) == pytest.approx((np.e, 1.0))


def test_zeta_max_is_sought_up_to_the_level_cap_only():
    """A jump of ζ at the last amplitude beyond the cap does not decide ζ_max; ω0_high still
    reads the whole usable backbone."""
    ds = backbone(2e-3, 1.5e-4, 2.195, 2.187)
    zeta = ds.zeta.values.copy()
    zeta[-1] = 3e-3                                          # a last-point jump, above the peak
    assert backbone_summary(ds.q_res_z, ds.omega0, zeta)["zeta_max"] == 3e-3
    capped = backbone_summary(ds.q_res_z, ds.omega0, zeta, max_level=4.5e-4)
    assert capped["zeta_max"] == pytest.approx(2e-3) and capped["q_at_zeta_max"] == pytest.approx(1.5e-4)
    assert capped["omega0_high"] == ds.omega0.values[-1]
    with pytest.raises(ValueError, match="no usable point with"):
        backbone_summary(ds.q_res_z, ds.omega0, zeta, max_level=1e-9)


def test_surrogate_vs_computed_reports_exact_and_shifted_predictions():
    computed = backbone(3.5e-3, 1e-4, 2.182, 2.17)
    exact = {k: computed[k].values.copy() for k in ("q_res_z", "omega0", "zeta", "gamma")}
    table = surrogate_vs_computed(exact, computed).set_index("quantity")
    assert np.allclose(table["error"], 0.0)
    shifted = dict(exact, zeta=1.01 * exact["zeta"])
    table = surrogate_vs_computed(shifted, computed).set_index("quantity")
    assert table.loc["zeta_max", "relative error (%)"] == pytest.approx(1.0)
    assert table.loc["omega0_low", "error"] == 0.0
    assert table.loc["zeta: largest error", "relative error (%)"] == pytest.approx(1.0)


def sobol(values_at_005, other=0.9):
    """Sobol dataset (output × parameter × level) with the paper's ζ indices at 0.05 mm."""
    outputs, params = ["omega0", "zeta", "gamma"], ["kappa1", "kappa2", "kappa3"]
    levels = [5e-5, 1e-4, 2e-4, 4e-4]
    data = {}
    for kind in ("first_order", "total_order"):
        a = np.full((3, 3, 4), other)
        a[1, :, 0] = values_at_005[kind]
        a[0, 0, :] = [1.0, 0.99, 0.995, 1.0] if other != 0.9 else 1.0
        data[kind] = variable(("output", "parameter", "level"), a, "1", kind)
    return xr.Dataset(data, coords={"output": outputs, "parameter": params,
                                    "level": variable("level", levels, "m", "amplitude level")})


def test_paper_comparison_rows_match_the_paper_when_we_equal_it():
    p = paper
    default = backbone(p.DEFAULT["zeta_max"][0], p.DEFAULT["q_at_zeta_max"][0], 2.195,
                       p.DEFAULT["omega0_at_zeta_max"][0])
    case_a = backbone(p.CASE_A["zeta_max"][0], 1e-4, p.CASE_A["omega0_low"][0], 2.17)
    optimum = backbone(p.OPTIMUM["zeta_max"][0], 1e-4, p.OPTIMUM["omega0_low"][0], 2.17)
    t3 = pd.DataFrame({"gamma_N": [1.0, 2.0, 3.0, 4.0], "default_eebm_mm": p.TABLE3["default_mm"],
                       "optimum_eebm_mm": p.TABLE3["optimum_mm"],
                       "reduction_eebm_pct": p.TABLE3["reduction_pct"],
                       "reduction_frf_pct": p.TABLE3["reduction_pct"]})
    table = paper_comparison(default, case_a, optimum, (1.0, -1.0, -1.0), t3, sobol(p.SOBOL_ZETA))
    numeric = table[table.quantity != "optimum κ"]
    assert np.allclose(numeric["ours / paper - 1 (%)"].astype(float), 0.0, atol=1e-9)
    assert (table.quantity.str.startswith("Sobol")).sum() == 7
    why = "where ours differ, and why"
    assert table.loc[table.quantity == "optimum κ", why].item() == "agrees (same corner)"
    assert table["paper source"].str.contains("§").all()
    assert table["where ours differ, and why"].str.startswith("agrees").all()
    shifted = paper_comparison(default, case_a, optimum, (1.0, -1.0, -0.5), t3,
                               sobol({k: np.array(v) + 0.1 for k, v in p.SOBOL_ZETA.items()}))
    s1 = shifted[shifted.quantity == "Sobol S1 of ζ to κ1 at 0.05 mm"]
    assert s1["ours"].item() == pytest.approx(0.51)
    assert s1["where ours differ, and why"].item().startswith("differs: at 0.05 mm")
    omega = sobol(p.SOBOL_ZETA, other=0.5).first_order          # S1(ω0, κ1) = 1, .99, .995, 1
    low = paper_comparison(default, case_a, optimum, (1.0, -1.0, -1.0), t3, sobol(p.SOBOL_ZETA, 0.5))
    assert omega.sel(output="omega0", parameter="kappa1").min() == 0.99
    assert low.loc[low.quantity.str.startswith("Sobol S1 of ω0"), "ours"].item() == pytest.approx(0.99)
    assert shifted.loc[shifted.quantity == "optimum κ", why].item().startswith("differs")


def test_html_table_escapes_text_and_rounds_numbers():
    page = html_table(pd.DataFrame({"name": ["a<b"], "x": [1.234567]}), "T & U", notes=["n"], digits=3)
    assert "a&lt;b" in page and "T &amp; U" in page and "<td>1.23</td>" in page and "n</p>" in page
