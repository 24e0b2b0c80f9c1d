"""Design of experiments: 27 factorial + maximin LHS training, named + LHS validation, seeded."""
import itertools

import numpy as np
from scipy.spatial.distance import cdist

from ringdamper.campaign.sampling import make_samples


def test_campaign_samples(campaign_config):
    s = campaign_config["sampling"]
    table = make_samples(s)
    train = table[table.split == "training"]
    val = table[table.split == "validation"]
    assert not (table.split == "reference").any()  # the factorial already holds every reference ring
    assert len(train) == 100 and len(val) == 20
    k_train = train[["kappa1", "kappa2", "kappa3"]].to_numpy()
    k_val = val[["kappa1", "kappa2", "kappa3"]].to_numpy()
    # the 27 factorial points are all there
    fact = np.array(list(itertools.product([-1.0, 0.0, 1.0], repeat=3)))
    assert np.allclose(cdist(fact, k_train).min(axis=1), 0.0)
    # the paper's named validation cases come first
    assert np.allclose(k_val[:3], s["named_validation"])
    # inside the box, no duplicates, validation disjoint from training
    assert np.all(np.abs(table[["kappa1", "kappa2", "kappa3"]].to_numpy()) <= 1.0)
    assert table.gid.is_unique
    assert cdist(k_val, k_train).min() > s["min_distance"]
    # LHS property: each of the 73 LHS training points falls in its own stratum per axis
    lhs = k_train[27:]
    for axis in range(3):
        strata = np.floor((lhs[:, axis] + 1.0) / 2.0 * 73).astype(int)
        assert len(set(strata)) == 73


def test_sampling_is_reproducible_and_seeded(campaign_config):
    s = dict(campaign_config["sampling"])
    a, b = make_samples(s), make_samples(s)
    assert a.equals(b)
    s["seed"] += 1
    assert not np.allclose(make_samples(s)[["kappa1"]], a[["kappa1"]])


def test_reference_rings_are_added_when_the_design_lacks_them(small_config):
    table = make_samples(small_config["sampling"])  # factorial levels -1, +1 only
    refs = table[table.split == "reference"]
    assert len(refs) == 7  # all but the paper optimum (1, -1, -1), a corner of the factorial
    assert refs.gid.str.startswith("r").all()
    assert ((refs[["kappa1", "kappa2", "kappa3"]] == 0).sum(axis=1) >= 2).all()
