"""Shared fixtures: the campaign configuration and a small test configuration."""
import copy
from pathlib import Path

import pytest

from ringdamper.config import load_config

TESTS = Path(__file__).resolve().parent


@pytest.fixture(scope="session")
def campaign_config():
    return load_config()


@pytest.fixture
def config(campaign_config):
    """A fresh, mutable copy of the campaign configuration."""
    return copy.deepcopy(campaign_config)


@pytest.fixture(scope="session")
def small_config():
    """The coarse configuration used by the Snakemake smoke test and CI."""
    return load_config(TESTS / "config_small.yaml")
