"""Contact-variety metric (ringdamper.studies.contact_state) on analytic contact states.

A ring on a rigid groove: the free ring grows by u = rho Omega^2 R^3 / E (thin ring, 2 % with
nu = 0.33: tests/static/test_static_stage.py). A uniform radial clearance below u closes every pair,
above it opens every pair with the gap c - u; a groove whose radius exceeds the ring's by
a (|s| - 1/3) outside the sector's central third (or a (1/3 - |s|) inside it), with a = 5 mm far
above the ring's displacement (below u), leaves exactly those pairs open, with gaps in [g0 - u, g0].
"""
import copy

import numpy as np
import pytest

from ringdamper.fem.model import build_model
from ringdamper.fem.prestress import rpm_to_rad_s
from ringdamper.geometry.sector import build_sector
from ringdamper.static.stage import solve_static, static_dataset
from ringdamper.studies.contact_state import (
    CENTRE,
    REFERENCE_RINGS,
    Variety,
    best_design,
    closure_summary,
    closure_supports,
    configured_design,
    contact_variety,
    design_config,
    score,
    support_label,
    support_of,
)

A = 5.0e-3  # m, slope of the groove profile per unit |s|


@pytest.fixture(scope="module")
def ring(campaign_config):
    cfg = copy.deepcopy(campaign_config)
    model = build_model(build_sector(cfg, (0.0, 0.0, 0.0)), cfg)
    half = np.pi / cfg["geometry"]["n_sectors"]
    s = np.round(np.abs(np.arctan2(model.pairs.position[:, 1], model.pairs.position[:, 0])) / half, 9)
    omega = rpm_to_rad_s(cfg["operation"]["speed_rpm"])
    g = cfg["geometry"]
    radius = g["disk"]["contact_radius"] - g["ring"]["thickness"] / 2
    u = cfg["material"]["density"] * omega**2 * radius**3 / cfg["material"]["young_modulus"]
    return cfg, model, half, s, u


def _variety(cfg, model, half, g0):
    result, prob = solve_static(model, cfg, rigid_blisk=True, g0=g0)
    assert result.status == 0, result.reason
    return contact_variety(static_dataset(model, result, prob, (0, 0, 0), 2081.0), half), result


@pytest.mark.parametrize("profile", ["outer", "centre"])
def test_groove_profile_gives_the_analytic_open_set(ring, profile):
    cfg, model, half, s, u = ring
    g0 = A * (np.maximum(s - CENTRE, 0.0) if profile == "outer" else np.maximum(CENTRE - s, 0.0))
    v, result = _variety(cfg, model, half, g0)
    g0[g0 < 1e-6 * A] = 0.0                                         # the stations at |s| = 1/3 touch
    expected_open = g0 > 0
    assert np.array_equal(~result.in_contact, expected_open)
    assert v.open_fraction == pytest.approx(expected_open.mean(), abs=1e-15)
    assert v.gap_position == pytest.approx(np.sum(g0 * s) / np.sum(g0), abs=0.01)  # gaps = g0 - O(um)
    assert np.all(result.gap[expected_open] <= g0[expected_open])
    assert np.all(result.gap[expected_open] >= g0[expected_open] - 1.02 * u)
    assert v.max_gap == pytest.approx(g0.max(), rel=0.01)
    if profile == "outer":
        assert v.centre_gap == 0.0 and v.outer_gap == v.max_gap
        assert v.n0_position <= CENTRE and v.peak_position <= CENTRE
    else:
        assert v.outer_gap == 0.0 and v.centre_gap == v.max_gap
        assert v.n0_position >= CENTRE and v.peak_position >= CENTRE - 1e-6


def test_uniform_clearance_opens_all_pairs_beyond_the_free_growth(ring):
    cfg, model, half, s, u = ring
    closed, _ = _variety(cfg, model, half, 0.9 * u)
    assert closed.open_fraction == 0.0 and closed.max_gap == 0.0
    assert closed.concentration == pytest.approx(1.0, abs=0.05)       # axisymmetric: uniform pressure
    opened, result = _variety(cfg, model, half, 1.1 * u)
    assert opened.open_fraction == 1.0 and opened.mean_pressure == 0.0
    assert result.gap == pytest.approx(0.1 * u, abs=0.02 * u)         # thin-ring growth to 2 %


def _v(open_fraction, max_gap, outer_gap, peak, concentration, n0_position, peak_position):
    return Variety(n_pairs=70, open_fraction=open_fraction, max_gap=max_gap, gap_position=0.8,
                   centre_gap=0.0, outer_gap=outer_gap, peak_pressure=peak, mean_pressure=peak / concentration,
                   concentration=concentration, n0_position=n0_position, peak_position=peak_position)


PAPER_LIKE = {  # a state set written from the paper's table (gaps in um, pressures in MPa)
    "default": _v(0.3, 2.0, 2.0, 1.0, 2.0, 0.4, 0.0),
    "kappa1=+1": _v(0.2, 1.0, 1.0, 1.1, 1.5, 0.45, 0.0),
    "kappa1=-1": _v(0.4, 3.0, 3.0, 1.1, 2.2, 0.4, 0.0),
    "kappa2=+1": _v(0.35, 4.0, 4.0, 1.8, 3.0, 0.3, 0.0),
    "kappa2=-1": _v(0.3, 2.0, 2.0, 0.9, 1.6, 0.5, 0.5),
    "kappa3=-1": _v(0.3, 3.0, 3.0, 2.0, 2.5, 0.3, 0.0),
    "paper optimum": _v(0.1, 1.0, 1.0, 1.5, 1.8, 0.45, 0.0),
}


def test_score_reads_the_paper_table_row_by_row():
    assert REFERENCE_RINGS.keys() == PAPER_LIKE.keys()
    assert all(score(PAPER_LIKE).values())
    broken = dict(PAPER_LIKE, **{"kappa3=-1": _v(0.3, 3.0, 3.0, 2.0, 2.5, 0.3, 0.5)})  # peak off-centre
    assert [k for k, ok in score(broken).items() if not ok] == ["kappa3=-1"]
    uniform = {k: _v(0.0, 0.0, 0.0, 1.0, 1.0, 0.5, 1.0) for k in PAPER_LIKE}    # all closed, uniform
    assert not any(score(uniform).values())


def test_best_design_is_the_cheapest_of_the_most_reproducing(campaign_config):
    """Most rows first; then the clearance nearest the configured 0 (an interference of 10 µm beats a
    clearance of 20 µm), the configured arm, kn nearest in log."""
    rows = [{"arm_thickness": a, "arm_length": length, "radial_clearance": c, "normal_stiffness_per_area": k,
             "rows_reproduced": n}
            for a, length, c, k, n in [(0.006, 0.02, 3e-5, 2e11, 2), (0.009, 0.02, 2e-5, 1e12, 2),
                                       (0.006, 0.02, 2e-5, 1e12, 2), (0.006, 0.01, -1e-5, 1e12, 2),
                                       (0.006, 0.02, -1e-5, 1e12, 2), (0.006, 0.02, 0.0, 7e10, 1)]]
    assert best_design(rows, campaign_config) is rows[4]
    assert best_design(rows[:4], campaign_config) is rows[3]
    assert best_design(rows[:3], campaign_config) is rows[2]


def test_design_config_moves_the_ring_with_the_arm(campaign_config):
    """A design changes only its own entries; kt keeps the configured kt/kn; the centred ring stays
    centred under an arm of another length (and the design is a valid configuration)."""
    from ringdamper.config import validate_config

    cfg = design_config(campaign_config, {"radial_clearance": -3e-5, "normal_stiffness_per_area": 2e11,
                                          "arm_thickness": 0.009, "arm_length": 0.012})
    g, c, c0 = cfg["geometry"], cfg["contact"], campaign_config["contact"]
    assert g["ring"]["radial_clearance"] == -3e-5 and g["disk"]["arm_thickness"] == 0.009
    assert g["disk"]["arm_length"] == 0.012
    arm_centre = g["disk"]["rim_axial_width"] / 2 + 0.012 / 2
    assert g["ring"]["axial_center"] == pytest.approx(arm_centre, abs=1e-12)
    assert c["tangential_stiffness_per_area"] / c["normal_stiffness_per_area"] == pytest.approx(
        c0["tangential_stiffness_per_area"] / c0["normal_stiffness_per_area"], rel=1e-12)
    validate_config(cfg)
    assert support_of(cfg) == {"arm_thickness": 0.009, "arm_length": 0.012}
    assert design_config(campaign_config, {}) == campaign_config


def test_closure_summary_separates_the_taper_from_the_sector_periodic_part():
    """An all-open state with closure d_n = 40 µm + 2 µm (z - z0) / (z1 - z0) + 0.07 µm |s| on a grid
    of 7 angles x 5 axial stations: mean 41.035 µm, axial spread 2 µm, periodic part +0.07 µm."""
    import xarray as xr

    half = np.pi / 30
    s, z = np.meshgrid(np.linspace(-1, 1, 7), np.linspace(0.03, 0.04, 5))
    s, z = s.ravel(), z.ravel()
    closure = 40e-6 + 2e-6 * (z - 0.03) / 0.01 + 0.07e-6 * np.abs(s)
    radius = 0.32
    static = xr.Dataset({"x": ("pair", radius * np.cos(s * half)), "y": ("pair", radius * np.sin(s * half)),
                         "z": ("pair", z), "initial_gap": ("pair", np.full(s.size, 1e-4)),
                         "gap": ("pair", 1e-4 - closure)})
    out = closure_summary(static, half)
    assert out["mean_closure"] == pytest.approx(40e-6 + 1e-6 + 0.07e-6 * np.mean(np.abs(s)), rel=1e-12)
    assert out["axial_spread"] == pytest.approx(2e-6, rel=1e-9)
    assert out["periodic_part"] == pytest.approx(0.07e-6, rel=1e-9)


def test_closure_supports_are_the_grid_then_the_configured_one(campaign_config):
    """The free-closure chart's supports: the grid's arm_thickness x arm_length, the configured support
    appended once when the grid lacks it; labelled in mm; the configured design is the model's."""
    cfg = copy.deepcopy(campaign_config)
    cfg["studies"]["contact_state"].update(arm_thickness=[0.004, 0.009], arm_length=[0.010])
    assert closure_supports(cfg) == [{"arm_thickness": 0.004, "arm_length": 0.010},
                                     {"arm_thickness": 0.009, "arm_length": 0.010}, support_of(cfg)]
    cfg["studies"]["contact_state"].update(arm_thickness=[support_of(cfg)["arm_thickness"]],
                                           arm_length=[support_of(cfg)["arm_length"]])
    assert closure_supports(cfg) == [support_of(cfg)]
    assert support_label({"arm_thickness": 0.0045, "arm_length": 0.02}) == "arm 4.5 x 20 mm"
    design = configured_design(cfg)
    assert design_config(cfg, design) == cfg
    assert design["radial_clearance"] == cfg["geometry"]["ring"]["radial_clearance"]
