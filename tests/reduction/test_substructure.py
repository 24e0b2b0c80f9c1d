"""The fixed substructure (reduction.superelement, reduction.substructured) against the monolithic
chain on the 1x mesh: static N0 and gaps to 1e-8 (the static condensation is exact), the lowest
stuck frequencies of ND 0 and ND 3 to 1e-5 (the truncation of the fixed part's modes and of both
chains' own), the file round trip, and which configuration edits the super-element depends on."""
import copy

import numpy as np
import pytest

from ringdamper.fem.contact_law import stuck_pair_stiffness
from ringdamper.fem.model import build_model
from ringdamper.geometry.sector import build_sector
from ringdamper.reduction.reduced import reduce_sector, stuck_frequencies
from ringdamper.reduction.substructured import SuperElementMismatch, morph_model, reduce_on_superelement
from ringdamper.reduction.superelement import blisk_config, build_superelement, load, save
from ringdamper.static.stage import solve_problem, solve_static, substructured_problem

KAPPA = (1.0, -1.0, -1.0)
N_LOWEST = 3   # stuck frequencies compared per ND
CLEARANCE = 3.0e-5   # m: some pairs stay open at speed


@pytest.fixture(scope="module")
def setup(campaign_config):
    config = copy.deepcopy(campaign_config)
    config["reduction"]["n_harmonics"] = 1                     # ND 0 and ND 3 (the target's)
    config["substructure"] = {"enabled": True, "n_modes": 100}
    config["geometry"]["ring"]["radial_clearance"] = CLEARANCE
    return config, build_superelement(config)


@pytest.fixture(scope="module")
def monolithic(setup):
    config, _ = setup
    return build_model(build_sector(config, KAPPA), config)


def test_static_contact_state_equals_the_monolithic_one(setup, monolithic):
    config, se = setup
    reference, _ = solve_static(monolithic, config)
    model, split = morph_model(config, KAPPA, se)
    result = solve_problem(substructured_problem(model, split, se, config), config["static"])
    assert reference.converged and result.converged
    assert 0 < reference.in_contact.sum() < len(reference.N0)       # open and closed pairs
    np.testing.assert_array_equal(result.in_contact, reference.in_contact)
    assert np.abs(result.N0 - reference.N0).max() <= 1e-8 * reference.N0.max()
    assert np.abs(result.gap - reference.gap).max() <= 1e-8 * reference.gap.max()
    d, d_ref = result.relative_displacement, reference.relative_displacement
    assert np.abs(d - d_ref).max() <= 1e-8 * np.abs(d_ref).max()


@pytest.mark.parametrize("pairs", [None, {"placement": "grid", "n_theta": 9, "n_axial": 4}])
def test_stuck_frequencies_equal_the_monolithic_ones(setup, monolithic, pairs):
    """Node pairs, and grid pairs (weights on the right cut folded per harmonic) on the same
    super-element: the pairs live in the morph zone, the fixed part never sees them."""
    config, se = setup
    if pairs is not None:
        config = copy.deepcopy(config)
        config["mesh"]["contact_pairs"] = pairs
        monolithic = build_model(build_sector(config, KAPPA), config)
    counts = {"n_fi": config["reduction"]["n_fixed_interface_modes"],
              "n_if": config["reduction"]["n_interface_modes"]}
    model, split = morph_model(config, KAPPA, se)
    sub = reduce_on_superelement(model, split, se, config["operation"]["engine_order"], **counts)
    mono = reduce_sector(monolithic, config["operation"]["engine_order"], n_harmonics=1, **counts)
    assert [h.size for h in sub.harmonics] == [h.size for h in mono.harmonics]
    for a, b in zip(sub.harmonics, mono.harmonics):
        np.testing.assert_array_equal(a.B, b.B)
    assert sub.response_index == mono.response_index
    kn, kt = stuck_pair_stiffness(monolithic.pairs.area, config["contact"], True)
    for a, b in zip(sub.harmonics, mono.harmonics):
        assert a.nd == b.nd
        f_sub = stuck_frequencies(a, kn, kt, N_LOWEST)
        f_mono = stuck_frequencies(b, kn, kt, N_LOWEST)
        assert np.abs(f_sub / f_mono - 1).max() < 1e-5, (a.nd, f_sub, f_mono)


def test_file_round_trip_and_the_checks_of_a_ring(setup, tmp_path):
    config, se = setup
    save(se, tmp_path / "fixed_part.npz")
    back = load(tmp_path / "fixed_part.npz")
    np.testing.assert_array_equal(back.boundary, se.boundary)
    for a, b in zip(back.K + back.M, se.K + se.M):
        np.testing.assert_array_equal(a, b)
    assert back.config_sha256 == se.config_sha256
    steel = copy.deepcopy(config)
    steel["material"]["density"] = 7800.0
    with pytest.raises(SuperElementMismatch, match="another blisk configuration"):
        morph_model(steel, KAPPA, back, "fixed_part.npz")
    thicker = copy.deepcopy(config)
    thicker["geometry"]["ring"]["thickness"] *= 1.2
    morph_model(thicker, KAPPA, back)                     # the ring's own dimension: same fixed part


def test_the_super_element_depends_on_the_blisk_not_on_the_ring(campaign_config):
    config = copy.deepcopy(campaign_config)
    base = blisk_config(config)
    for section, key, value in (("material", "young_modulus", 1.1e11), ("operation", "speed_rpm", 3000.0)):
        edited = copy.deepcopy(config)
        edited[section][key] = value
        assert blisk_config(edited) != base, (section, key)
    for key, value in (("thickness", 0.005), ("radial_clearance", 1e-5)):
        edited = copy.deepcopy(config)
        edited["geometry"]["ring"][key] = value
        assert blisk_config(edited) == base, key
    edited = copy.deepcopy(config)
    edited["geometry"]["ring"]["axial_center"] += 1e-3     # moves the groove in the arm's mesh
    assert blisk_config(edited) != base
