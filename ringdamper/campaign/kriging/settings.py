"""The ``surrogate`` settings of the Kriging fit: defaults and validation.

Scale bounds are tied to the width w = 2 of the κ domain: θ_k ∈ scale_bounds × w, default
[0.05, 5] × 2 = [0.1, 10]. Below 0.1 the correlation between neighbouring training points (spacing
≈ 0.4 for 100 points in 3-D) vanishes and the model degenerates into spikes. Above ~10 the likelihood of
a smooth response keeps rising along a flat ridge (θ, σ → ∞ together) while R becomes ill-conditioned:
the predictive variance collapses and round-off enters the interpolation, for no gain in accuracy
(docs/surrogate.md, *Scale bounds*). The squared-exponential kernel is worse conditioned still; give it a
nugget (~1e-8) if used. The campaign's configuration raises the lower bound to 0.3 and estimates the
nugget: its top amplitudes scatter between solution branches (docs/surrogate.md, *Branch scatter*).

The nugget factor ν is fixed (default 1e-12, OpenTURNS' own round-off floor) or, given as [low, high],
estimated by maximum likelihood (profiled and polished with θ, see :mod:`.fit`).

``transform`` names, per output, the scale the Gaussian process models (:mod:`.transform`): ``log``
(z = ln(y + c), c = ``log_offset`` × the model's largest training value) for the outputs that physics
keeps non-negative and that come close to 0 against their spread (ζ is 0 in the stuck regime; γ and
|q_res,z| are positive), ``identity`` for ω0 (2.17-2.20, a spread of 1 % of its value: no model
comes near 0). Outputs not named use ``identity``.
"""

from __future__ import annotations

import numpy as np

from .gp import KERNELS
from .transform import TRANSFORMS

DOMAIN_WIDTH = 2.0  # κ ∈ [-1, 1]
DEFAULT_SETTINGS = {
    "kernel": "matern52",        # correlation function, one of KERNELS
    "n_starts": 8,               # multistart size of the likelihood maximisation
    "seed": 0,                   # seed of the starting points (OpenTURNS RandomGenerator)
    "scale_bounds": (0.05, 5.0),  # θ bounds as multiples of the κ-domain width (2)
    "nugget": 1.0e-12,           # fixed nugget factor ν ≥ 0, or [low, high] to estimate it by ML
    "min_training": 10,          # fewer usable points than this: the model is not fitted (status 2)
    "transform": {"q_res_z": "log", "omega0": "identity", "zeta": "log", "gamma": "log"},  # per output
    "log_offset": 1.0,           # c of the log transform, × the model's largest training value
}


def check_settings(settings: dict | None) -> dict:
    """Settings with defaults filled in; a clear error naming the ``surrogate.<key>`` otherwise."""
    s = {**DEFAULT_SETTINGS, **(settings or {})}
    unknown = sorted(set(s) - set(DEFAULT_SETTINGS))
    if unknown:
        raise ValueError(f"surrogate: unknown keys {unknown}; allowed {sorted(DEFAULT_SETTINGS)}")
    if s["kernel"] not in KERNELS:
        raise ValueError(f"surrogate.kernel = {s['kernel']!r}; allowed {KERNELS}")
    for key, low in (("n_starts", 1), ("seed", 0), ("min_training", 2)):
        if not isinstance(s[key], (int, np.integer)) or s[key] < low:
            raise ValueError(f"surrogate.{key} = {s[key]!r}; must be an integer >= {low}")
    lo_hi = np.asarray(s["scale_bounds"], dtype=float)
    if lo_hi.shape != (2,) or not (0.0 < lo_hi[0] < lo_hi[1] < np.inf):
        raise ValueError(f"surrogate.scale_bounds = {s['scale_bounds']!r}; must be [low, high] with 0 < low < high")
    nugget = np.asarray(s["nugget"], dtype=float)
    if nugget.shape == ():
        if not 0.0 <= nugget < 1.0:
            raise ValueError(f"surrogate.nugget = {s['nugget']!r}; a fixed nugget must be in [0, 1)")
    elif nugget.shape != (2,) or not (0.0 < nugget[0] < nugget[1] < 1.0):
        raise ValueError(f"surrogate.nugget = {s['nugget']!r}; "
                         "an estimated nugget needs [low, high], 0 < low < high < 1")
    if not isinstance(s["transform"], dict):
        raise ValueError(f"surrogate.transform = {s['transform']!r}; must map output names to one of {TRANSFORMS}")
    transform = {**DEFAULT_SETTINGS["transform"], **s["transform"]}
    for out, kind in transform.items():
        if kind not in TRANSFORMS:
            raise ValueError(f"surrogate.transform.{out} = {kind!r}; allowed {TRANSFORMS}")
    if not isinstance(s["log_offset"], (int, float, np.floating)) or not 0.0 < s["log_offset"] < np.inf:
        raise ValueError(f"surrogate.log_offset = {s['log_offset']!r}; must be a number > 0")
    return {**s, "scale_bounds": tuple(lo_hi), "nugget": float(nugget) if nugget.shape == () else tuple(nugget),
            "transform": transform, "log_offset": float(s["log_offset"])}
