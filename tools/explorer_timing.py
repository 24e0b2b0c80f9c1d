"""Responsiveness of the design explorer page in headless Chromium (Debian's ``chromium`` and
``chromedriver``, driven by selenium): the time to interactive, from the start of navigation to the end
of the page's first draw (``performance.now()`` when every model is factorised and every panel drawn),
and the redraw time of a slider move: the page's own update (predict, every panel redrawn, the URL
written) and the time to the next animation frame after it.

    python -m tools.explorer_timing results/explorer.html [--loads 5] [--moves 40]

Prints the median and the largest value of each over ``loads`` openings and ``moves`` key presses on
the κ1 slider (1400 × 1750 window).
"""
from __future__ import annotations

import argparse
import shutil
import statistics
from pathlib import Path


def measure(page: Path, loads: int, moves: int) -> dict:
    from selenium import webdriver
    from selenium.webdriver.chrome.options import Options
    from selenium.webdriver.chrome.service import Service
    from selenium.webdriver.common.by import By
    from selenium.webdriver.common.keys import Keys
    from selenium.webdriver.support.ui import WebDriverWait

    options = Options()
    options.binary_location = shutil.which("chromium")
    for arg in ("--headless=new", "--no-sandbox", "--disable-gpu", "--window-size=1400,1750"):
        options.add_argument(arg)
    driver = webdriver.Chrome(options=options, service=Service(shutil.which("chromedriver")))
    interactive, redraw, frame = [], [], []
    try:
        for _ in range(loads):
            driver.get("about:blank")
            driver.get(page.resolve().as_uri())
            WebDriverWait(driver, 30).until(lambda d: d.execute_script("return document.body.dataset.ready === '1'"))
            interactive.append(driver.execute_script("return explorer.timing.interactive_ms"))
        slider = driver.find_element(By.ID, "slider-k1")
        driver.execute_script("explorer.timing.redraw_ms.length = 0; explorer.timing.redraw_frame_ms.length = 0")
        for _ in range(moves):
            slider.send_keys(Keys.ARROW_RIGHT)
        WebDriverWait(driver, 30).until(lambda d: d.execute_script(
            f"return explorer.timing.redraw_frame_ms.length >= {moves}"))
        timing = driver.execute_script("return explorer.timing")
        redraw, frame = timing["redraw_ms"], timing["redraw_frame_ms"]
    finally:
        driver.quit()
    return {"interactive_ms": interactive, "redraw_ms": redraw, "redraw_to_frame_ms": frame}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("page", type=Path)
    parser.add_argument("--loads", type=int, default=5)
    parser.add_argument("--moves", type=int, default=40)
    args = parser.parse_args(argv)
    print(f"{args.page} ({args.page.stat().st_size / 1e6:.2f} MB)")
    for name, values in measure(args.page, args.loads, args.moves).items():
        print(f"{name}: median {statistics.median(values):.1f}, max {max(values):.1f} ({len(values)} samples)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
