"""Fidelity study: the extrapolation and read-out on analytic oracles, the harmonic error shrinking
with H on a friction oscillator, and the study rules on the coarse test configuration."""
import copy

import numpy as np
import pandas as pd
import pytest
import yaml

from ringdamper.fem.model import build_model
from ringdamper.geometry.sector import build_sector
from ringdamper.nonlinear.harmonic_balance.eebm import eebm
from ringdamper.nonlinear.harmonic_balance.epmc import epmc
from ringdamper.studies.fidelity.mesh_backbone import mesh_config
from ringdamper.studies.fidelity.quantities import relative_errors, richardson, user_quantities
from ringdamper.studies.fidelity.summary import choose
from ringdamper.studies.fidelity.surrogate import backbone_dataset, lhs_design
from tests.nonlinear.systems import one_dof
from tests.snakemake_run import REPO, failure_tail, run_snakemake


def test_richardson_recovers_an_analytic_limit_and_order():
    h = np.array([1.0, 1 / 2, 1 / 3])
    f0, p = richardson(h, 936.0 + 5.7 * h**1.2)
    assert f0 == pytest.approx(936.0, rel=1e-12) and p == pytest.approx(1.2, rel=1e-9)
    f0, p = richardson(h, 10.0 - 3.0 * h**2)          # convergence from below
    assert f0 == pytest.approx(10.0, rel=1e-12) and p == pytest.approx(2.0, rel=1e-9)
    with pytest.raises(ValueError, match="not monotone"):
        richardson(h, [1.0, 2.0, 1.5])


def test_user_quantities_of_a_synthetic_backbone():
    q = np.geomspace(1e-5, 1e-3, 41)
    zeta = 1e-3 * np.exp(-np.log(q / 2e-4) ** 2)      # peak 1e-3 at q = 0.2 mm (parabola in log q)
    freq = 900.0 - 10.0 * np.log(q / 1e-5)
    gamma = 1e4 * q                                   # monotone: q at gamma is gamma / 1e4
    out = user_quantities(backbone_dataset(np.arange(41.0), q, zeta, freq, gamma), [5e-5, 4e-4], [0.5, 2.0, 50.0])
    assert out["zeta_max"] == pytest.approx(1e-3, rel=1e-3)
    assert out["q_at_zeta_max"] == pytest.approx(2e-4, rel=1e-3)
    assert out["freq_low"] == pytest.approx(900.0 - 10.0 * np.log(5.0), rel=1e-12)
    assert out["q_gamma_1"] == pytest.approx(5e-5, rel=1e-2) and out["q_gamma_2"] == pytest.approx(2e-4, rel=1e-2)
    assert np.isnan(out["q_gamma_3"])                 # beyond the backbone
    spike = zeta.copy()
    spike[-1] = 5e-3                                  # a last-point jump above the read-out range
    capped = user_quantities(backbone_dataset(np.arange(41.0), q, spike, freq, gamma), [5e-5, 4e-4], [], 4.5e-4)
    assert capped["zeta_max"] == pytest.approx(1e-3, rel=1e-3)
    assert relative_errors({"a": np.nan}, {"a": 1.0})["a"] == np.inf


def test_harmonic_error_shrinks_with_H_on_a_friction_oscillator():
    """One mass with a Jenkins element: zeta_max and the high-amplitude frequency of H = 1, 3, 5
    against H = 9; the error falls with H (odd harmonics only: the law is odd) and H = 1 is already
    within 5 % (the describing function is a good first approximation)."""
    alpha = np.geomspace(0.02, 2.0, 25)

    def quantities(H):
        st, c = one_dof(H=H)
        res = eebm(epmc(st, c, alpha, H=H, nt=64 if H < 9 else 128), zeta_s=1e-4)
        ds = backbone_dataset(alpha, res.q_res_peak, res.zeta, res.frequency, res.gamma)
        return user_quantities(ds, [0.05, 0.8], [])

    ref = quantities(9)
    errs = [max(relative_errors(quantities(H), ref).values()) for H in (1, 3, 5)]
    assert errs[0] > errs[1] > errs[2] and errs[0] < 0.05


def test_lhs_design_draws_distinct_pool_points_spread_over_the_box():
    rng = np.random.default_rng(0)
    pool = rng.uniform(-1, 1, (100, 3))
    idx = lhs_design(pool, 20, seed=1)
    assert len(set(idx)) == 20
    for j in range(3):                                # one pick per fifth of each axis, roughly
        assert len(np.unique(np.digitize(pool[idx, j], [-0.6, -0.2, 0.2, 0.6]))) == 5


SMALL_FIDELITY = {
    "rings": [{"name": "default", "kappa": [0.0, 0.0, 0.0]}],
    "dials": [{"name": "harmonics", "key": "dnnm.n_harmonics", "values": [1, 3]},
              {"name": "amplitudes", "key": "dnnm.n_amplitudes", "values": [5, 8, 16]}],
    "mesh_levels": [[1, 1], [2, 1], [3, 1]],
    "mesh_families": ["1D", "1B"],
    "mesh_backbone": {"factors": [1, 2], "n_harmonics": 1, "n_time_samples": 16,
                      "contact_pairs": {"placement": "grid", "n_theta": 4, "n_axial": 2}},
    "training_sizes": [5, 8],
    "tolerance": 0.01,
}


@pytest.mark.slow
def test_fidelity_rules_run_on_the_coarse_configuration(tmp_path):
    """dials.csv, mesh.csv and mesh_backbone.csv of a two-dial, one-ring study on the coarse mesh
    (8-node bricks). Both meshes of the backbone study carry the same grid of pairs, and the refined
    one, being a conforming refinement, a softer structure: the backbone's frequency at the lowest
    response level drops."""
    small = yaml.safe_load((REPO / "tests" / "config_small.yaml").read_text())
    (tmp_path / "config.yaml").write_text(yaml.safe_dump({**small, "fidelity": SMALL_FIDELITY}))
    fid = tmp_path / "results" / "fidelity"
    run = run_snakemake(tmp_path / "results", tmp_path / "config.yaml", fid / "dials.csv", fid / "mesh.csv",
                        fid / "mesh_backbone.csv", cores=2, timeout=600)
    assert run.returncode == 0, failure_tail(run)
    dials = pd.read_csv(fid / "dials.csv")
    assert len(dials) == 5 and set(dials.dial) == {"harmonics", "amplitudes"}
    assert (dials[dials.is_reference].error_max == 0).all()
    assert dials[dials.is_default].value.tolist() == [1, 8]     # config_small: H = 1, 8 amplitudes
    assert (dials.chain_cpu_s > 0).all() and (dials.peak_rss_mb > 50).all()
    h = dials[dials.dial == "harmonics"].set_index("value")
    assert h.dnnm_cpu_s[3] > h.dnnm_cpu_s[1]                    # more harmonics cost more
    mesh = pd.read_csv(fid / "mesh.csv").sort_values("factor")
    limits = pd.read_csv(fid / "mesh_limits.csv")
    f1d = limits.set_index("family").limit_hz["1D"]
    assert mesh.frequency_1D.is_monotonic_decreasing and f1d < mesh.frequency_1D.min()   # from above
    assert abs(mesh.error_1D.iloc[-1]) < abs(mesh.error_1D.iloc[0])
    backbone = pd.read_csv(fid / "mesh_backbone.csv").set_index("factor")
    assert backbone.pairs[2] == backbone.pairs[1] == 8 and backbone.error_max[2] == 0
    assert backbone.freq_low[2] < backbone.freq_low[1]
    assert np.isfinite(backbone.zeta_max).all() and (backbone.zeta_max > 0).all()


def test_mesh_backbone_keeps_its_contact_pairs_on_every_mesh(small_config):
    """With ``fidelity.mesh_backbone.contact_pairs`` the refined meshes carry the same grid of pairs
    (same count, same positions to the mesh's discretisation of the surface); without it the node
    pairs refine with the mesh."""
    cfg = {**small_config, "fidelity": {"mesh_backbone": copy.deepcopy(SMALL_FIDELITY["mesh_backbone"])}}
    pairs = [build_model(build_sector(c, (0.0, 0.0, 0.0)), c).pairs for c in (mesh_config(cfg, f) for f in (1, 2))]
    assert len(pairs[0]) == len(pairs[1]) == 8
    assert np.abs(pairs[0].position - pairs[1].position).max() < 1e-3 * np.abs(pairs[0].position).max()
    cfg["fidelity"]["mesh_backbone"].pop("contact_pairs")
    nodes = [len(build_model(build_sector(c, (0.0, 0.0, 0.0)), c).pairs) for c in (mesh_config(cfg, f) for f in (1, 2))]
    assert nodes[1] > nodes[0]


def test_choice_is_the_cheapest_accurate_setting_beyond_timing_noise():
    def row(value, cpu, err, ref=False):
        return {"dial": "d", "value": value, "chain_cpu_s": cpu, "error_max": err, "is_reference": ref}

    rows = [row(1, 5.0, 0.05), row(2, 10.0, 0.004), row(3, 10.5, 0.0001), row(5, 40.0, 0.0, True)]
    assert choose(rows, 0.01, {"d": 5}) == {"d": 3}          # 2 and 3 cost the same: the accurate one
    assert choose(rows, 0.01, {"d": 3}) == {"d": 3}
    rows[2]["chain_cpu_s"] = 9.5                              # 3 is now cheapest, and current
    rows[1]["chain_cpu_s"] = 9.0
    assert choose(rows, 0.01, {"d": 3}) == {"d": 3}           # 2 saves < 10 %: keep the current one
    assert choose(rows, 1e-6, {"d": 3}) == {"d": 5}           # nothing accurate enough: the reference
