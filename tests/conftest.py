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


CAMPAIGN_GROUP = "small_campaign"


@pytest.hookimpl(tryfirst=True)  # before pytest-xdist's, which writes the groups into the test ids
def pytest_collection_modifyitems(items):
    """Under ``pytest -n 2 --dist loadgroup`` (``make test``), the tests of a module go to one worker,
    so that its module-scoped fixtures (a campaign run, a reduced model) are built once; the modules
    that use the session's small campaign go together to one worker, which builds it once. Snakemake
    runs of different modules may overlap: each writes into a results folder of its own, Snakemake's
    incomplete markers in the repository's ``.snakemake`` are per output file, and the runs take no
    locks (``tests/snakemake_run.py``)."""
    campaign_modules = {item.module for item in items if "small_campaign" in getattr(item, "fixturenames", ())}
    for item in items:
        module = getattr(item, "module", None)
        if module is not None:
            group = CAMPAIGN_GROUP if module in campaign_modules else module.__name__
            item.add_marker(pytest.mark.xdist_group(group))
