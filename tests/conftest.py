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


SNAKEMAKE_GROUP = "snakemake"


def pytest_collection_modifyitems(items):
    """Under ``pytest -n 2 --dist loadgroup`` (``make test``), every test that runs Snakemake goes to
    one worker, one after another: they share the session's small campaign and the repository's
    ``.snakemake`` metadata (locks, incomplete markers), and each already uses both cores. The other
    tests spread over the workers around them."""
    for item in items:
        module = getattr(item, "module", None)
        runs_snakemake = module is not None and any(
            hasattr(module, name) for name in ("run_snakemake", "snakemake_command"))
        if runs_snakemake or "small_campaign" in getattr(item, "fixturenames", ()):
            item.add_marker(pytest.mark.xdist_group(SNAKEMAKE_GROUP))
