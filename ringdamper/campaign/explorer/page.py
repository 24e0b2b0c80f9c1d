"""The design explorer page: one self-contained HTML file (no network request) of the page template, its
style sheet and scripts (``assets/``) and the data of :mod:`.payload`, inlined as JSON.

The plots are plain SVG drawn by ``assets/plot.js``: no plotting library, so the page stays small
and adds no dependency (docs/explorer.md).
"""

from __future__ import annotations

import json
from pathlib import Path

from ...io import written_whole

ASSETS = Path(__file__).parent / "assets"
MAX_BYTES = 10 * 2**20  # the page must stay a file one can mail


def inline_json(data: dict) -> str:
    """``data`` as JSON that is safe inside a <script> element (no ``</`` sequence) and strict (no NaN)."""
    return json.dumps(data, allow_nan=False, separators=(",", ":")).replace("</", "<\\/")


def render(data: dict) -> str:
    """The page's HTML: the template with the style, the scripts and the data inlined."""
    page = (ASSETS / "page.html").read_text()
    parts = {"/*STYLE*/": (ASSETS / "explorer.css").read_text(),
             "/*PLOT_JS*/": (ASSETS / "plot.js").read_text(),
             "/*KRIGING_JS*/": (ASSETS / "kriging.js").read_text(),
             "/*EXPLORER_JS*/": (ASSETS / "explorer.js").read_text(),
             "/*DATA*/": inline_json(data)}
    for marker, text in parts.items():
        if page.count(marker) != 1:
            raise ValueError(f"{ASSETS / 'page.html'}: marker {marker} must occur once")
        page = page.replace(marker, text)
    return page


def write_page(data: dict, path) -> int:
    """Write the page of ``data`` to ``path``, whole or not at all; its size in bytes (at most MAX_BYTES)."""
    html = render(data).encode()
    if len(html) > MAX_BYTES:
        raise ValueError(f"{path}: the explorer page would be {len(html) / 2**20:.1f} MiB, "
                         f"more than {MAX_BYTES / 2**20:.0f} MiB")
    with written_whole(path) as part:
        Path(part).write_bytes(html)
    return len(html)
