"""Design of experiments of the paper design: 27 factorial + maximin LHS training, named + LHS validation,
seeded (the adaptive design: test_adaptive.py)."""
import itertools

import numpy as np
import pandas as pd
import pytest
from scipy.spatial.distance import cdist

from ringdamper.campaign.design_space import read_samples
from ringdamper.campaign.sampling import make_samples


def test_campaign_samples(campaign_config):
    s = {**campaign_config["sampling"], "design": "paper"}
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
    table = make_samples({**small_config["sampling"], "design": "paper"})  # factorial levels -1, +1 only
    refs = table[table.split == "reference"]
    assert len(refs) == 7  # all but the paper optimum (1, -1, -1), a corner of the factorial
    assert refs.gid.str.startswith("r").all()
    assert ((refs[["kappa1", "kappa2", "kappa3"]] == 0).sum(axis=1) >= 2).all()


@pytest.fixture
def samples_csv(tmp_path, campaign_config):
    """A valid samples.csv of the campaign design, to be spoiled by each test."""
    path = tmp_path / "samples.csv"
    make_samples(campaign_config["sampling"]).to_csv(path, index=False)
    return path


def spoil(path, edit):
    edit(pd.read_csv(path)).to_csv(path, index=False)
    return path


def test_a_valid_samples_file_reads_back(samples_csv, campaign_config):
    assert read_samples(samples_csv).equals(make_samples(campaign_config["sampling"]))


def test_duplicate_gid_is_refused_naming_the_rows(samples_csv):
    spoil(samples_csv, lambda t: t.assign(gid=t.gid.where(t.index != 5, t.gid[2])))
    with pytest.raises(ValueError, match=r"samples\.csv: gid 't002' appears in rows \[2, 5\]"):
        read_samples(samples_csv)


def test_kappa_outside_the_box_is_refused_naming_row_field_and_range(samples_csv):
    spoil(samples_csv, lambda t: t.assign(kappa2=t.kappa2.where(t.index != 4, 1.5)))
    with pytest.raises(ValueError, match=r"row 4 \(gid 't004'\): kappa2 = 1\.5 is outside the allowed "
                                         r"range \[-1, 1\]"):
        read_samples(samples_csv)


def test_missing_column_is_refused_naming_it(samples_csv):
    spoil(samples_csv, lambda t: t.drop(columns="kappa3"))
    with pytest.raises(ValueError, match=r"missing column\(s\) \['kappa3'\]"):
        read_samples(samples_csv)


def test_a_named_validation_case_outside_the_box_is_refused_at_design_time(campaign_config):
    s = {**campaign_config["sampling"], "named_validation": [[0.0, -1.2, 0.0]]}
    with pytest.raises(ValueError, match=r"kappa2 = -1\.2 is outside the allowed range \[-1, 1\]"):
        make_samples(s)
