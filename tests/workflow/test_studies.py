"""`make studies` on a small setting: every study rule runs on the coarse test configuration with
small study grids, and its outputs agree with the library and with physics (the calibrated hub
thickness reaches the operating speed; the mesh study's reference level has zero error and linear bricks are stiffer;
more modes never make the reduced target frequency worse; the contact calibration's chosen set is the one of
``contact:``; the contact-state search covers its grid, and while every pair of the default ring stays
closed its preload is linear in the clearance, interference included). The EPMC's time-domain check
(rule ``epmc_time_domain``: no settings to make small, minutes of CPU) is left out; its functions are
tested in tests/nonlinear/test_shooting.py."""
import numpy as np
import pandas as pd
import pytest
import xarray as xr
import yaml

from tests.snakemake_run import REPO, failure_tail, run_snakemake

SMALL_STUDIES = {
    "hub_calibration": {"bracket": [0.01, 0.03], "xtol": 1.0e-5},
    "contact_calibration": {
        "amplitudes": [2.0e-6, 4.0e-4, 8],
        "coarse": {"friction_coefficient": [0.3, 0.8], "normal_stiffness_per_area": [1.0e+11],
                   "kt_over_kn": [0.5]},
        "refine": {"friction_coefficient": [0.3], "normal_stiffness_per_area": [1.0e+12],
                   "kt_over_kn": [1.0]},
        "runner_up": {"friction_coefficient": 0.8, "normal_stiffness_per_area": 1.0e+11, "kt_over_kn": 0.5},
        "harmonics": [1],
        "example_curves": [[0.8, 1.0e+11, 0.5]]},
    "mesh_convergence": {"levels": [[1, 1], [1, 2]]},
    "reduction_convergence": {"n_fixed_interface_modes": [10, 20], "n_interface_modes": [5, 10],
                              "band": [0.99, 1.0]},
    "last_point": {"points_below": 2, "n_points": 4, "n_harmonics": 3},   # reduced.nc has H = 3 here
    "contact_state": {"radial_clearance": [-2.0e-5, 0.0, 2.0e-5, 4.4e-5], "normal_stiffness_per_area": [7.0e+10],
                      "arm_thickness": [0.006], "arm_length": [0.012, 0.020], "free_clearance": 1.0e-4,
                      "backbone_clearance": [-1.0e-5], "backbone_friction": [0.7]},
}


@pytest.mark.slow
def test_study_rules_run_on_a_small_setting(tmp_path):
    config = yaml.safe_load((REPO / "tests" / "config_small.yaml").read_text())
    config["studies"] = SMALL_STUDIES
    path = tmp_path / "config.yaml"
    path.write_text(yaml.safe_dump(config))
    out = tmp_path / "results"
    run = run_snakemake(out, path, "studies", "--omit-from", "epmc_time_domain", cores=2, timeout=1500)
    assert run.returncode == 0, failure_tail(run)
    studies = out / "studies"

    hub = yaml.safe_load((studies / "hub_calibration.yaml").read_text())
    assert 0.01 < hub["hub_thickness_m"] < 0.03
    assert hub["crossing_speed_rpm"] == pytest.approx(config["operation"]["speed_rpm"], rel=1e-3)

    mesh = pd.read_csv(studies / "mesh_convergence.csv")
    assert list(zip(mesh.factor, mesh.order)) == [(1, 1), (1, 2)]
    assert mesh.relative_error.iloc[1] == 0.0                      # the quadratic level is the reference
    assert mesh.frequency_hz.iloc[0] > mesh.frequency_hz.iloc[1]   # linear bricks lock: too stiff

    red = pd.read_csv(studies / "reduction_convergence.csv")
    assert len(red) == 4 and (red.target_error >= 0).all()
    for n_if, rows in red.groupby("n_if"):
        assert rows.sort_values("n_fi").target_error.is_monotonic_decreasing
    assert (studies / "reduction_convergence.md").read_text().startswith("| n_fi |")

    campaign_trace, fine_trace = (xr.open_dataset(studies / "last_point" / f"{name}.nc")
                                  for name in ("campaign", "fine"))
    grid = campaign_trace.amplitude.values
    assert fine_trace.amplitude.values == pytest.approx(np.geomspace(grid[-3], grid[-1], 4), rel=1e-12)
    assert fine_trace.attrs["n_harmonics"] == 3
    for trace in (campaign_trace, fine_trace):
        usable = np.isin(trace.status.values, (0, 3))
        assert usable[0]
        ratio, n_open = trace.normal_force_ratio_min.values[usable], trace.lifting_pairs.values[usable]
        assert np.all(np.isfinite(ratio)) and np.all((n_open > 0) == (ratio <= 0))
    assert (studies / "last_point" / "last_point_separation.png").stat().st_size > 0

    cc = studies / "contact_calibration"
    coarse = pd.read_csv(cc / "coarse.csv")
    assert len(coarse) == 2 and set(coarse.friction_coefficient) == {0.3, 0.8}
    chosen = pd.read_csv(cc / "harmonics_A.csv")
    assert chosen.friction_coefficient.tolist() == [config["contact"]["friction_coefficient"]]
    assert np.isfinite(chosen.objective).all()
    assert (cc / "calibration_default_backbone.png").stat().st_size > 0

    cs = studies / "contact_state"
    designs, rings = pd.read_csv(cs / "contact_state_designs.csv"), pd.read_csv(cs / "contact_state_rings.csv")
    assert len(designs) == 8 and len(rings) == 7 * 8 and designs.rows_reproduced.between(0, 7).all()
    assert set(designs.arm_length) == {0.012, 0.02} and designs.radial_clearance.min() == -2.0e-5
    default = rings[rings.ring == "default"].set_index(["arm_length", "radial_clearance"]).sort_index()
    for length in (0.012, 0.02):
        p = default.loc[length].mean_pressure
        assert (default.loc[length].open_fraction.loc[:2.0e-5] == 0).all()
        assert p[-2.0e-5] > p[0.0] > p[2.0e-5] > 0                    # interference raises the preload
        assert p[-2.0e-5] - p[0.0] == pytest.approx(p[0.0] - p[2.0e-5], rel=1e-8)   # linear while closed
    backbone = pd.read_csv(cs / "contact_state_backbone.csv")
    assert backbone.radial_clearance.tolist() == [-1.0e-5]
    for name in ("search", "maps_configured", "maps_best", "free_closure", "backbone"):
        assert (cs / f"contact_state_{name}.png").stat().st_size > 0
