"""The design explorer: one self-contained HTML page (``results/explorer.html``) in which the user moves
κ and sees the Kriging-predicted backbones with their bands, the nearest computed rings, the forcing
view, κ-space and the nearest ring's contact maps (docs/explorer.md).

Modules:

- :mod:`.payload`: the page's data from dataset.nc, kriging.nc, optimum.yaml and the static.nc files
  (the models' parameters, never a precomputed prediction), with the checks of those inputs;
- :mod:`.page`: the HTML file, with the style, the scripts of ``assets/`` and the data inlined.
"""

from .page import MAX_BYTES, render, write_page
from .payload import RING_SPLITS, page_data, read_input

__all__ = ["MAX_BYTES", "RING_SPLITS", "page_data", "read_input", "render", "write_page"]
