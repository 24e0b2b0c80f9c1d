"""The analytics rules of the Snakefile on a synthetic results tree of the test configuration:
samples.csv and analytic dnnm.nc files (one geometry failed, one held by the gauge) stand in for the
per-geometry chain, which Snakemake does not rerun."""
import numpy as np
import pytest
import yaml

from ringdamper.campaign.sampling import make_samples
from ringdamper.io import check_contract, read_netcdf
from ringdamper.nonlinear.stage import amplitude_grid, failed_dnnm
from tests.snakemake_run import failure_tail, run_snakemake

from .synthetic import dnnm_dataset, write_campaign

TARGETS = ["surrogate/validation.nc", "surrogate/validation_metrics.csv", "surrogate/oat.nc",
           "surrogate/optimum.yaml", "surrogate/grid.nc", "sensitivity/sobol_global.nc",
           "sensitivity/sobol_local.nc", "sensitivity/sobol_indices.csv",
           "figures/fig13_predicted_vs_computed.png", "figures/fig13_validation_backbones.png",
           "figures/fig14_kappa1.png", "figures/fig15_kappa2.png", "figures/fig16_kappa3.png",
           "figures/fig17_envelopes.png", "figures/fig18_sobol_global.png", "figures/fig20_sobol_local.png"]


@pytest.mark.slow
def test_analytics_rules_on_a_synthetic_campaign(tmp_path, small_config):
    """On the fixed (paper) design: the adaptive rounds would ask for rings no synthetic file holds."""
    out = tmp_path / "results"
    config = {**small_config, "sampling": {**small_config["sampling"], "design": "paper"}}
    config_file = tmp_path / "config.yaml"
    config_file.write_text(yaml.safe_dump(config))
    samples = make_samples(config["sampling"])
    out.mkdir()
    samples.to_csv(out / "samples.csv", index=False)
    alpha = amplitude_grid(small_config["dnnm"])
    k = samples.set_index("gid")[["kappa1", "kappa2", "kappa3"]]
    overrides = {"t004": failed_dnnm(small_config, k.loc["t004"], "RuntimeError: static solve failed", 3),
                 "t006": dnnm_dataset(k.loc["t006"], alpha, [0] * (alpha.size - 3) + [3] * 3)}
    write_campaign(out, samples, alpha, overrides)
    run = run_snakemake(out, config_file, *[out / t for t in TARGETS])
    assert run.returncode == 0, failure_tail(run)
    assert not (out / "logs" / "dnnm").exists()  # the per-geometry chain was not rerun

    dataset = read_netcdf(out / "campaign" / "dataset.nc")
    check_contract(dataset)
    assert dataset.sizes["geometry"] == len(samples) and int(dataset.held.sum()) == 3
    assert "t004 (training) excluded at 8 of 8 amplitudes" in (out / "logs" / "kriging.log").read_text()

    fit = read_netcdf(out / "surrogate" / "kriging.nc")
    assert "t004" not in fit.geometry.values[fit.training_mask.values.any(axis=0)]

    val = read_netcdf(out / "surrogate" / "validation.nc")
    check_contract(val)
    assert np.all(np.isfinite(val.r2)) and np.all(np.isfinite(val.q2))
    assert np.all((val.coverage >= 0) & (val.coverage <= 1))

    optimum = yaml.safe_load((out / "surrogate" / "optimum.yaml").read_text())
    assert len(optimum["kappa"]) == 3 and all(-1 <= v <= 1 for v in optimum["kappa"])
    assert isinstance(optimum["criterion"], str)
    assert optimum["predicted"]["zeta_max"] >= optimum["default_predicted"]["zeta_max"]
    assert optimum["predicted"]["q_res_z_at_zeta_max"] > 0

    grid = read_netcdf(out / "surrogate" / "grid.nc")
    check_contract(grid)
    assert grid.zeta_max.shape == (12, 12, 12)
    assert float(grid.zeta_max.max()) == pytest.approx(optimum["grid"]["best_node_zeta_max"])

    for study in ("global", "local"):
        sobol = read_netcdf(out / "sensitivity" / f"sobol_{study}.nc")
        check_contract(sobol)
        assert dict(sobol.sizes) == {"output": 3, "parameter": 3, "level": 3}
        for kind in ("first_order", "total_order"):
            v, lo, hi = (sobol[f"{kind}{s}"].values for s in ("", "_lower", "_upper"))
            assert np.all(np.isfinite(v)) and np.all(lo <= v) and np.all(v <= hi)
            assert np.all(hi >= 0) and np.all(lo <= 1)  # within [0, 1] up to the interval
    assert "first_order_pce" in read_netcdf(out / "sensitivity" / "sobol_global.nc")
    for t in TARGETS:
        assert (out / t).stat().st_size > 0
