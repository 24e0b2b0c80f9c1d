"""End to end: the coarse test configuration through the whole campaign to results/report.html
(every geometry, the analytics, the optimum as a real geometry, the forced responses, Table 3 and
the report), with assertions on the contents of the files."""
import numpy as np
import pandas as pd
import pytest
import yaml

from ringdamper.io import read_netcdf
from ringdamper.logs import cpu_record, read_cpu_seconds


@pytest.fixture(scope="module")
def campaign(small_campaign):
    """The whole small campaign and its report (tests/workflow/conftest.py)."""
    return small_campaign


def _check_units(ds):
    for name in list(ds.data_vars) + list(ds.coords):
        assert {"units", "long_name"} <= set(ds[name].attrs), name


@pytest.mark.slow
def test_dataset_and_surrogates(campaign, small_config):
    ds = read_netcdf(campaign / "campaign" / "dataset.nc")
    assert set(ds.sizes) >= {"geometry", "amplitude"}
    assert ds.sizes["amplitude"] == small_config["dnnm"]["n_amplitudes"]
    assert {"kappa1", "kappa2", "kappa3", "split"} <= set(ds.coords)
    samples = pd.read_csv(campaign / "samples.csv")
    assert set(ds.geometry.values) == set(samples.gid)            # the gid is the geometry coordinate
    _check_units(ds)
    usable = np.isin(ds.status.values, (0, 3))
    assert usable.mean() > 0.9 and np.isfinite(ds.zeta.values[usable]).all()
    val = pd.read_csv(campaign / "surrogate" / "validation_metrics.csv")
    assert len(val) >= 4 and np.isfinite(val.select_dtypes("number").to_numpy()).any()


@pytest.mark.slow
def test_sobol_indices_within_unit_interval(campaign):
    """Every index lies within its confidence interval, and the interval meets [0, 1]."""
    for name in ("sobol_global", "sobol_local"):
        ds = read_netcdf(campaign / "sensitivity" / f"{name}.nc")
        assert {"output", "parameter", "level"} <= set(ds.first_order.dims)
        assert {"omega0", "zeta", "gamma"} <= set(ds.output.values)
        _check_units(ds)
        for kind in ("first_order", "total_order"):
            value, lower, upper = (ds[f"{kind}{suffix}"].values for suffix in ("", "_lower", "_upper"))
            assert np.isfinite(value).all()
            assert np.all(lower <= value + 1e-12) and np.all(value <= upper + 1e-12)
            assert np.all(upper >= -1e-9) and np.all(lower <= 1 + 1e-9)


@pytest.mark.slow
def test_optimum_is_computed_at_the_optimum_kappa(campaign):
    kappa = yaml.safe_load((campaign / "surrogate" / "optimum.yaml").read_text())["kappa"]
    assert len(kappa) == 3 and all(-1 <= k <= 1 for k in kappa)
    for stage in ("static", "reduced", "dnnm"):
        ds = read_netcdf(campaign / "geometry" / "optimum" / f"{stage}.nc")
        assert np.allclose(ds.attrs["kappa"], kappa, atol=1e-12), stage
    dnnm = read_netcdf(campaign / "geometry" / "optimum" / "dnnm.nc")
    assert dnnm.status.values[0] == 0 and np.isfinite(dnnm.zeta.values[0])
    check = pd.read_csv(campaign / "surrogate" / "optimum_check.csv").set_index("quantity")
    assert np.isfinite(check.loc["zeta_max", ["predicted", "computed", "error"]].astype(float)).all()


@pytest.mark.slow
def test_forced_responses_and_table3(campaign, small_config):
    targets = small_config["frf"]["target_amplitudes"]
    levels = yaml.safe_load((campaign / "frf" / "levels.yaml").read_text())
    assert len(levels["gamma_N"]) == len(targets) and np.all(np.diff(levels["gamma_N"]) > 0)
    table = pd.read_csv(campaign / "frf" / "table3.csv")
    assert list(table.level) == list(range(1, len(targets) + 1))
    assert np.allclose(table.gamma_N, levels["gamma_N"])
    assert table.default_eebm_mm.to_numpy() == pytest.approx(1e3 * np.array(targets), rel=1e-9)
    numbers = table.drop(columns=["level"]).to_numpy(float)
    assert np.isfinite(numbers).all()
    # coarse model (H = 1, coarse mesh): forced peaks within 10 % of the E-EBM
    assert np.all(np.abs(table[["default_frf_vs_eebm_pct", "optimum_frf_vs_eebm_pct"]]) < 10.0)
    for gid in ("optimum", *[p.name for p in (campaign / "frf").iterdir() if p.is_dir()]):
        for level in range(1, len(targets) + 1):
            ds = read_netcdf(campaign / "frf" / gid / f"gamma_{level}.nc")
            _check_units(ds)
            assert ds.amplitude.dims == ("point",) and ds.sizes["point"] > 10
            assert ds.amplitude.attrs["units"] == "m" and ds.frequency.attrs["units"] == "Hz"
            assert np.isfinite(ds.amplitude).all() and np.isfinite(ds.frequency).all()
            assert float(ds.peak_amplitude) == pytest.approx(float(ds.amplitude.max()), rel=0.02)


@pytest.mark.slow
def test_report_holds_every_figure_and_table(campaign):
    html = (campaign / "report.html").read_text()
    figures = sorted(p.name for p in (campaign / "figures").glob("*.png"))
    tables = sorted(p.name for p in (campaign / "tables").glob("*.html"))
    assert {"optimum_maps.png", "optimum_backbones_frf.png", "optimum_surrogate_check.png"} <= set(figures)
    assert {"table3.html", "paper_comparison.html", "validation_metrics.html", "sobol_global.html",
            "sobol_local.html", "optimum.html", "optimum_check.html"} <= set(tables)
    for name in figures + tables + ["explorer.html"]:
        assert name in html, name
    comparison = pd.read_csv(campaign / "tables" / "paper_comparison.csv")
    assert comparison["paper source"].str.contains("§").all()
    n_levels = min(len(pd.read_csv(campaign / "frf" / "table3.csv")), 4)     # the paper has four
    assert comparison.quantity.str.startswith("Table 3").sum() == 4 * n_levels


@pytest.mark.slow
def test_the_campaign_ran_adaptively_in_rounds_to_its_budget(campaign, small_config):
    """The small configuration's adaptive design: rounds of 2 rings from the 10 initial ones, stopped by
    the budget of 14 (not an error: the report says so), the design figure and comparison table in the
    report, the validation rings untouched."""
    from ringdamper.campaign.sampling import make_samples

    adaptive = small_config["sampling"]["adaptive"]
    records = [yaml.safe_load(p.read_text()) for p in sorted((campaign / "adaptive").glob("round_*.yaml"))]
    assert len(records) >= 3 and [r["round"] for r in records] == list(range(1, len(records) + 1))
    assert all(len(r["chosen"]) == adaptive["batch"] and not r["stop"] for r in records[:-1])
    assert records[-1]["stop"] and records[-1]["reason"] == "budget" and records[-1]["n_computed"] == adaptive["n_max"]
    samples = pd.read_csv(campaign / "samples.csv")
    initial = make_samples(small_config["sampling"])
    head = samples.iloc[:len(initial)]
    assert head.gid.tolist() == initial.gid.tolist() and head.split.tolist() == initial.split.tolist()
    kappa = ["kappa1", "kappa2", "kappa3"]
    assert np.allclose(head[kappa], initial[kappa], rtol=1e-9, atol=1e-10)     # written with 10 digits
    chosen = [c["gid"] for r in records for c in r["chosen"]]
    assert samples.gid.iloc[len(initial):].tolist() == chosen
    assert (samples.split == "training").sum() == adaptive["n_max"]
    for gid in chosen:
        assert read_netcdf(campaign / "geometry" / gid / "dnnm.nc", "dnnm").status.values[0] == 0
    kriging = read_netcdf(campaign / "surrogate" / "kriging.nc")
    assert int(kriging["n_training"].max()) == adaptive["n_max"]
    row = pd.read_csv(campaign / "tables" / "design_row.csv").iloc[0]
    assert row.design == "adaptive" and row.n_training == adaptive["n_max"] and row.stop == "budget"
    assert row.job_cpu_s > 0 and 0 < row.zeta_max_computed
    # the job CPU is the jobs' own records, one per chain job, at most both cores for the whole wall time
    jobs = [f"{stage}/{gid}" for gid in samples.gid for stage in ("static", "reduced", "dnnm")]
    jobs += [f"adaptive/round_{r['round']}" for r in records]
    job_cpu = [read_cpu_seconds(cpu_record(campaign / "logs" / f"{job}.log")) for job in jobs]
    assert None not in job_cpu
    assert row.job_cpu_s == pytest.approx(sum(job_cpu), rel=1e-5) and row.job_cpu_s <= 2 * row.job_wall_s
    assert "ran before CPU records existed" not in (campaign / "tables" / "design_comparison.html").read_text()
    per_lu = row.job_cpu_s / row.reference_lu_s       # three values written to 6 digits: each within 5e-6
    assert row.reference_lu_s > 0 and row.job_cpu_reference_lus == pytest.approx(per_lu, rel=1.5e-5)
    html = (campaign / "report.html").read_text()
    for name in ("design_by_round.png", "stopping_trace.png", "design_comparison.html", "adaptive_rounds.html"):
        assert name in html, name
    assert "budget sampling.adaptive.n_max = 14 ran out" in (campaign / "tables" / "design_comparison.html").read_text()
