"""Logging of the rule scripts: the library's ``logging`` records go to the rule's log file."""
from __future__ import annotations

import logging


def to_file(path) -> logging.Logger:
    """Send INFO and above of every logger to ``path`` (overwritten); return the root logger."""
    handler = logging.FileHandler(path, mode="w")
    handler.setFormatter(logging.Formatter("%(asctime)s %(levelname)s %(name)s: %(message)s"))
    root = logging.getLogger()
    root.handlers[:] = [handler]
    root.setLevel(logging.INFO)
    return root
