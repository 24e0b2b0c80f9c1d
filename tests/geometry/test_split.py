"""The sector's split into a fixed part and a morph zone (geometry.split): over the 27 corner rings
kappa in {-1, 0, 1}^3 the fixed part and its interface are where they are at kappa = 0, bit for
bit, so one reduction of the fixed part serves every ring; the contact nodes are in the morph zone."""
import itertools

import numpy as np
import pytest

from ringdamper.fem.model import build_model
from ringdamper.geometry.sector import BODY_RING, PART_ARM, PART_RING, build_sector
from ringdamper.geometry.split import element_nodes, split_sector
from ringdamper.studies.mesh_convergence import refined

CORNERS = list(itertools.product((-1.0, 0.0, 1.0), repeat=3))


@pytest.fixture(scope="module", params=[1, 2], ids=["1x", "2x"])
def split(request, campaign_config):
    config = refined(campaign_config, request.param)
    return config, split_sector(config)


def test_fixed_part_and_interface_do_not_move_over_the_corners(split):
    config, s = split
    order = config["mesh"]["element_order"]
    sector = build_sector(config, (0.0, 0.0, 0.0))
    reference, elements = element_nodes(sector, order)
    fixed_nodes = np.unique(elements[:, s.fixed_elements])
    ring_nodes = np.unique(elements[:, sector.body == BODY_RING])
    moved_somewhere = np.zeros(len(reference), dtype=bool)
    for kappa in CORNERS:
        positions, connectivity = element_nodes(build_sector(config, kappa), order)
        assert np.array_equal(connectivity, elements)
        assert np.array_equal(positions[fixed_nodes], reference[fixed_nodes]), kappa
        moved_somewhere |= np.any(positions != reference, axis=1)
    moved_somewhere[ring_nodes] = False
    # the blisk nodes that move at some corner are exactly the split's moving nodes
    assert np.array_equal(np.flatnonzero(moved_somewhere), s.moving_nodes)
    assert len(s.moving_nodes) and not np.intersect1d(s.moving_nodes, s.interface_nodes).size


def test_morph_zone_is_the_ring_and_arm_elements_around_the_band(split):
    config, s = split
    sector = build_sector(config, (0.0, 0.0, 0.0))
    parts = sector.part[s.morph_elements]
    assert np.all(np.isin(parts, (PART_RING, PART_ARM)))
    assert np.array_equal(np.flatnonzero(sector.part == PART_RING), s.morph_elements[parts == PART_RING])
    assert np.all(sector.body[s.fixed_elements] != BODY_RING)
    assert len(s.fixed_elements) + len(s.morph_elements) == len(sector.part)
    assert len(s.interface_nodes) > 0


def test_contact_nodes_are_in_the_morph_zone_and_off_the_interface(split):
    config, s = split
    model = build_model(build_sector(config, (1.0, -1.0, 1.0)), config)
    _, elements = element_nodes(model.geometry, config["mesh"]["element_order"])
    morph_nodes = np.unique(elements[:, s.morph_elements])
    contact = np.concatenate([model.pairs.ring_node, model.pairs.blisk_node])
    assert np.all(np.isin(contact, morph_nodes))
    assert not np.intersect1d(contact, s.interface_nodes).size
    assert not np.intersect1d(model.tip_node, morph_nodes).size      # the forcing node is fixed
