"""Acquisition of a round: how much a candidate ring would teach the surrogates and how likely it is to
beat the current optimum.

Exploration, the predictive uncertainty of the quantities users read along the backbone (zeta, gamma,
|q_res,z|, omega0), each normalised by the spread of its training values at that amplitude:

    U(x) = mean over outputs o and amplitudes a of  s_o(a, x) / sd_o(a)     (a with sd_o(a) > 0).

Exploitation, the expected improvement (Jones, Schonlau & Welch 1998, J. Glob. Optim. 13: 455-492) of
the optimum criterion, zeta_max up to |q_res,z| = exploration.optimum_max_level
(:func:`~ringdamper.campaign.exploration.predicted_zeta_max`), over the current predicted optimum f*.
zeta_max(x) is read at the amplitude node j*(x) where the predicted mean backbone reaches it, with mean
mu = zeta(j*, x) and standard deviation s = s_zeta(j*, x):

    EI(x) = (mu - f*) Phi(z) + s phi(z),   z = (mu - f*) / s.

Score: a(x) = U(x) / max U + w EI(x) / max(max EI, EI_FLOOR |f*|) (maxima over the candidate set;
w = ``sampling.adaptive.exploit_weight``), so both terms span [0, 1] whatever the outputs' units; the
floor keeps an expected gain below 0.1 % of the optimum (round-off where the optimum sits on a training
ring) from being blown up to a full term.
"""
from __future__ import annotations

import numpy as np
from scipy.stats import norm

from ..exploration import Backbones, predicted_zeta_max

EXPLORED_OUTPUTS = ("zeta", "gamma", "q_res_z", "omega0")
EI_FLOOR = 1.0e-3  # relative to the current optimum's zeta_max


def uncertainty(bb: Backbones, spread: dict) -> np.ndarray:
    """(point,) U(x) of the module docstring."""
    terms = []
    for out in EXPLORED_OUTPUTS:
        sd = spread[out]
        use = np.isfinite(sd) & (sd > 0)
        terms.append(bb.std[out][use] / sd[use, None])
    return np.nanmean(np.vstack(terms), axis=0)


def zeta_max_distribution(bb: Backbones, q_max: float) -> tuple[np.ndarray, np.ndarray]:
    """(point,) mean and standard deviation of the predicted zeta_max (at the node j*)."""
    mu, j = predicted_zeta_max(bb, q_max)
    s = np.take_along_axis(bb.std["zeta"], j[None], 0)[0]
    return mu, s


def expected_improvement(mu: np.ndarray, s: np.ndarray, best: float) -> np.ndarray:
    """EI of the module docstring; max(mu - f*, 0) where s = 0."""
    gain = mu - best
    s = np.where(np.isfinite(s), s, 0.0)
    z = np.divide(gain, s, out=np.zeros_like(gain), where=s > 0)
    return np.where(s > 0, gain * norm.cdf(z) + s * norm.pdf(z), np.maximum(gain, 0.0))


def _unit(v: np.ndarray, floor: float = 0.0) -> np.ndarray:
    top = max(np.nanmax(v) if v.size else 0.0, floor)
    return v / top if top > 0 else np.zeros_like(v)


def acquisition(bb: Backbones, spread: dict, q_max: float, best: float, weight: float) -> dict:
    """Per candidate: ``explore`` U, ``exploit`` EI and the ``score`` a of the module docstring."""
    explore = uncertainty(bb, spread)
    exploit = expected_improvement(*zeta_max_distribution(bb, q_max), best)
    score = _unit(explore) + weight * _unit(exploit, EI_FLOOR * abs(best))
    return {"explore": explore, "exploit": exploit, "score": np.nan_to_num(score, nan=-np.inf)}
