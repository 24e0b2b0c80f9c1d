"""The explorer page's inputs and file: a missing or foreign dataset.nc / kriging.nc fails naming the
file; the page inlines its data as strict JSON (no NaN), makes no network request and stays small."""
import json
import re

import pytest
import xarray as xr

from ringdamper.campaign.design_space import REFERENCE_RINGS
from ringdamper.campaign.explorer import MAX_BYTES, page_data
from ringdamper.io import InputFileError

from .campaign import ALPHA, N_UNREACHED, build_page, build_tree


@pytest.fixture(scope="module")
def tree(tmp_path_factory):
    root = tmp_path_factory.mktemp("explorer_inputs")
    paths = build_tree(root)
    return root, paths


def data_of(paths, **replace):
    p = {**paths, **replace}
    return page_data(p["dataset"], p["kriging"], p["optimum"], p["static"], REFERENCE_RINGS, 5e-5)


def test_missing_inputs_are_named(tree):
    root, paths = tree
    for key in ("dataset", "kriging"):
        missing = root / "nowhere" / f"{key}.nc"
        with pytest.raises(InputFileError, match=re.escape(str(missing)) + ": missing"):
            data_of(paths, **{key: missing})


def test_foreign_inputs_are_named(tree):
    root, paths = tree
    # each file in the other's place, and a NetCDF of neither kind
    with pytest.raises(InputFileError, match=re.escape(str(paths["dataset"])) + ": not a ringdamper kriging.nc"):
        data_of(paths, kriging=paths["dataset"])
    with pytest.raises(InputFileError, match=re.escape(str(paths["kriging"])) + ": not a ringdamper dataset.nc"):
        data_of(paths, dataset=paths["kriging"])
    text = root / "not_netcdf.nc"
    text.write_text("kappa = 1\n")
    with pytest.raises(InputFileError, match=re.escape(str(text))):
        data_of(paths, kriging=text)


def test_the_page_inlines_parameters_only_and_makes_no_request(tree):
    root, paths = tree
    data = data_of(paths)
    kriging = xr.open_dataset(paths["kriging"])
    zeta = data["models"]["zeta"]
    assert len(zeta) == ALPHA.size and zeta[-1] is None and all(m is not None for m in zeta[:-1])
    assert zeta[0]["sigma"] == 0 and all(m["sigma"] > 0 for m in zeta[1:-1])  # stuck at the lowest amplitude
    assert len(zeta[0]["z"]) == int(kriging.n_training.sel(output="zeta").values[0]) == 12
    assert len(zeta[0]["rows"]) == 12 and int(kriging.n_training.values[0, -1]) == 12 - N_UNREACHED
    assert {r["split"] for r in data["rings"]} == {"training", "validation"} and len(data["rings"]) == 16
    html = build_page(paths, root / "explorer.html").read_text()
    assert len(html.encode()) < MAX_BYTES
    payload = re.search(r'<script type="application/json" id="explorer-data">(.*?)</script>', html, re.S).group(1)
    json.loads(payload, parse_constant=lambda c: pytest.fail(f"non-strict JSON constant {c}"))
    assert not re.search(r"(src|href)\s*=|https?://|@import|fetch\(|XMLHttpRequest", html)
    assert "default-src 'none'" in html  # the browser refuses any request the page might make
