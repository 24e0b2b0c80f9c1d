"""The campaign's sample table (``samples.csv``): the paper's fixed design
(:func:`~.design_space.paper_design`) or the adaptive design's initial table
(:func:`~.adaptive.design.adaptive_samples`), as ``sampling.design`` says.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from .adaptive.design import adaptive_samples
from .design_space import REFERENCE_RINGS, SAMPLE_COLUMNS, check_samples, paper_design


def make_samples(sampling: dict) -> pd.DataFrame:
    """Table ``gid, kappa1, kappa2, kappa3, split`` of the campaign known before any job runs:
    training, validation, and the reference rings the design does not already hold (split
    ``reference``, gids r000...). ``sampling.design``: ``paper`` (the whole fixed design) or
    ``adaptive`` (the initial design and the validation rings; the rounds add the rest,
    :mod:`ringdamper.campaign.adaptive`)."""
    if sampling.get("design", "paper") == "adaptive":
        return adaptive_samples(sampling)
    training, validation = paper_design(sampling)
    rows = [(f"t{i:03d}", *k, "training") for i, k in enumerate(training)]
    rows += [(f"v{i:03d}", *k, "validation") for i, k in enumerate(validation)]
    design = np.vstack([training, validation])
    missing = [k for k in REFERENCE_RINGS.values() if not np.any(np.all(design == k, axis=1))]
    rows += [(f"r{i:03d}", *k, "reference") for i, k in enumerate(missing)]
    return check_samples(pd.DataFrame(rows, columns=list(SAMPLE_COLUMNS)), "the sampling design")
