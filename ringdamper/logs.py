"""The log of a rule script: the library's ``logging`` records and the interpreter's stderr go to the
rule's log file, so that warnings, tracebacks and the script's own records land in one place."""
from __future__ import annotations

import logging
import sys
from pathlib import Path


def to_file(path) -> logging.Logger:
    """Send stderr and INFO and above of every logger to ``path`` (overwritten); return the root
    logger, for the script's own records."""
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    sys.stderr = open(path, "w", buffering=1)
    handler = logging.StreamHandler(sys.stderr)
    handler.setFormatter(logging.Formatter("%(asctime)s %(levelname)s %(name)s: %(message)s"))
    root = logging.getLogger()
    root.handlers[:] = [handler]
    root.setLevel(logging.INFO)
    return root
