"""A screenshot of the explorer page at a given κ: headless Chromium (Debian's ``chromium``) opens the
page with κ in its URL fragment and writes a PNG of the window."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

WINDOW = (1400, 1600)  # px: the whole page at the layout's three panels per row


def screenshot(page, kappa, path, window=WINDOW, timeout: float = 120.0) -> Path:
    """PNG of ``page`` (explorer.html) at ``kappa`` (3 values) written to ``path``; a clear error when
    chromium is not installed or writes no file."""
    chromium = shutil.which("chromium")
    if chromium is None:
        raise RuntimeError("chromium not found: install Debian's chromium (apt-get install chromium)")
    page, path = Path(page).resolve(), Path(path).resolve()
    if not page.is_file():
        raise FileNotFoundError(f"{page}: missing (the explorer page)")
    path.parent.mkdir(parents=True, exist_ok=True)
    path.unlink(missing_ok=True)
    url = page.as_uri() + "#k=" + ",".join(f"{float(k):.6g}" for k in kappa)
    cmd = [chromium, "--headless=new", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
           f"--window-size={window[0]},{window[1]}", f"--screenshot={path}", url]
    run = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    if run.returncode != 0 or not path.is_file():
        raise RuntimeError(f"chromium wrote no screenshot {path} (exit {run.returncode}): {run.stderr[-2000:]}")
    return path
