"""The design explorer in a real browser (Debian's chromium + chromium-driver, driven by selenium): its
predictions equal KrigingSurrogate's, a slider redraws the curves, an out-of-range κ is clamped and
flagged, a shared URL restores its κ, and the page never shows NaN. Marker ``browser``: not part of
``make test``; run by ``make test-explorer`` (docs/explorer.md)."""
import shutil

import numpy as np
import pytest
import xarray as xr

from ringdamper.campaign.kriging import OUTPUTS, KrigingSurrogate

from .campaign import ALPHA, FAILED_STATIC, build_page, build_tree

pytestmark = pytest.mark.browser
RTOL = 1e-9  # browser against numpy, relative; values clipped near 0 compare to RTOL x the output's scale
CHROMIUM, CHROMEDRIVER = shutil.which("chromium"), shutil.which("chromedriver")


@pytest.fixture(scope="module")
def tree(tmp_path_factory):
    root = tmp_path_factory.mktemp("explorer")
    paths = build_tree(root)
    return paths, build_page(paths, root / "explorer.html")


@pytest.fixture(scope="module")
def browser():
    if not (CHROMIUM and CHROMEDRIVER):
        pytest.fail("chromium and chromedriver are needed: apt-get install chromium chromium-driver")
    from selenium import webdriver
    from selenium.webdriver.chrome.options import Options
    from selenium.webdriver.chrome.service import Service

    options = Options()
    options.binary_location = CHROMIUM
    for arg in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                "--window-size=1400,1800"):
        options.add_argument(arg)
    driver = webdriver.Chrome(options=options, service=Service(CHROMEDRIVER))
    yield driver
    driver.quit()


def open_page(browser, page, fragment=""):
    from selenium.webdriver.support.ui import WebDriverWait

    browser.get("about:blank")  # a new document even when only the fragment differs
    browser.get(page.as_uri() + fragment)
    WebDriverWait(browser, 20).until(lambda d: d.execute_script("return document.body.dataset.ready === '1'"))


def test_predictions_equal_the_python_surrogate(tree, browser):
    paths, page = tree
    open_page(browser, page)
    X = np.random.default_rng(7).uniform(-1, 1, (50, 3))
    js = browser.execute_script("return arguments[0].map((k) => explorer.predict(k))", X.tolist())
    ref = KrigingSurrogate(xr.open_dataset(paths["kriging"])).predict(X)
    for out in OUTPUTS:
        scale = float(np.nanmax(np.abs(ref[out].values)))
        for key, name in (("median", out), ("lower", f"{out}_lower"), ("upper", f"{out}_upper")):
            got = np.array([[np.nan if v is None else v for v in p[out][key]] for p in js]).T  # (amplitude, point)
            want = ref[name].values
            assert got.shape == want.shape == (ALPHA.size, 50)
            np.testing.assert_array_equal(np.isnan(got), np.isnan(want), err_msg=f"{name}: models differ")
            np.testing.assert_allclose(got, want, rtol=RTOL, atol=RTOL * scale, err_msg=name)
    assert np.isnan(ref["zeta"].values[-1]).all()  # the top amplitude has no model: compared as missing above
    assert np.all(ref["zeta"].values[0] == 0) and np.all(ref["zeta_upper"].values[0] == 0)  # the constant model


def test_a_slider_move_redraws_the_curves(tree, browser):
    from selenium.webdriver.common.by import By
    from selenium.webdriver.common.keys import Keys

    _, page = tree
    open_page(browser, page)
    drawn = ("curve-zeta", "band-zeta", "curve-forcing")
    paths = {el: browser.find_element(By.ID, el).get_attribute("d") for el in drawn}
    slider = browser.find_element(By.ID, "slider-k1")
    slider.send_keys(*[Keys.ARROW_RIGHT] * 30)
    kappa = browser.execute_script("return explorer.kappa()")
    np.testing.assert_allclose(kappa, [0.3, 0.0, 0.0], atol=1e-12)
    for el, before in paths.items():
        after = browser.find_element(By.ID, el).get_attribute("d")
        assert after and after != before, f"{el} not redrawn"
    assert browser.find_element(By.ID, "input-k1").get_attribute("value") == "0.3"
    assert browser.execute_script("return location.hash") == "#k=0.3,0,0"


def test_an_out_of_range_input_is_clamped_and_flagged(tree, browser):
    from selenium.webdriver.common.by import By
    from selenium.webdriver.common.keys import Keys

    _, page = tree
    open_page(browser, page)
    note = browser.find_element(By.ID, "clamp-note")
    assert not note.is_displayed()
    field = browser.find_element(By.ID, "input-k2")
    field.clear()
    field.send_keys("-3.5", Keys.ENTER)
    assert browser.execute_script("return explorer.kappa()") == [0, -1, 0]
    assert field.get_attribute("value") == "-1"
    assert note.is_displayed() and "κ2 = -3.5 is outside [−1, 1]: clamped to -1" in note.text
    open_page(browser, page, "#k=0.2,7,-0.4")
    assert browser.execute_script("return explorer.kappa()") == [0.2, 1, -0.4]
    assert "clamped to 1" in browser.find_element(By.ID, "clamp-note").text


def test_a_shared_url_restores_its_kappa(tree, browser):
    from selenium.webdriver.common.by import By

    _, page = tree
    open_page(browser, page, "#k=0.3,-0.5,0.8")
    assert browser.execute_script("return explorer.kappa()") == [0.3, -0.5, 0.8]
    assert [browser.find_element(By.ID, f"slider-k{i}").get_attribute("value") for i in (1, 2, 3)] == \
        ["0.3", "-0.5", "0.8"]
    assert not browser.find_element(By.ID, "clamp-note").is_displayed()
    open_page(browser, page)  # no fragment: the default ring
    assert browser.execute_script("return explorer.kappa()") == [0, 0, 0]


def test_the_page_says_where_there_is_no_model_and_never_shows_nan(tree, browser):
    from selenium.webdriver.common.by import By

    paths, page = tree
    failed = xr.open_dataset(paths["dataset"]).sel(geometry=FAILED_STATIC)
    at_failed = "#k=" + ",".join(str(float(failed[f"kappa{i}"])) for i in (1, 2, 3))
    for fragment in ("", "#k=1,1,1", "#k=-1,-1,-1", at_failed):
        open_page(browser, page, fragment)
        text = browser.find_element(By.TAG_NAME, "body").text
        assert "no model at 1 of 8 amplitudes" in text and "ζ: constant model at 1 amplitude (" in text
        assert "NaN" not in text and "NaN" not in browser.page_source
    assert f"nearest computed ring {FAILED_STATIC} (validation)" in text and "its static solve failed" in text
    assert browser.find_element(By.ID, "map-pressure").find_elements(By.TAG_NAME, "circle") == []
    assert browser.execute_script("return performance.getEntriesByType('resource').length") == 0  # offline
    timing = browser.execute_script("return explorer.timing")
    print(f"\nexplorer timing (ms): interactive {timing['interactive_ms']:.0f}, redraw {timing['redraw_ms']}")
