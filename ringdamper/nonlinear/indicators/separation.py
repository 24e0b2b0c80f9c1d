"""Contact-separation indicator of a backbone (docs/nonlinear_core.md §4.3).

How far the preloaded pairs are from opening, per amplitude:

    n_min(α) = min over preloaded pairs p and time t of  N_p(t) / N0_p,
    N_p(t) = N0_p + kn_p d_n,p(t)                                  (unclipped normal force),

1 in the stuck linear regime, crossing 0 where the first pair lifts off for part of the period; the
pairs with ``min_t N_p/N0_p ≤ 0`` are the *lifting* pairs. Where pairs lift off, the unilateral
law clips the normal force, which feeds harmonics above any truncation: on the default ring the
top grid amplitude (42 lifting pairs) gives γ 15.6 N at H = 3 and 11.9 N at H = 5, while the
highest-harmonic energy fraction (:mod:`ringdamper.nonlinear.indicators.truncation`) stays at 5e-5 there, below
its threshold. So lift-off is reported by itself (:func:`warn_separation`). A few lifting pairs are
harmless: on the campaign's optimum pairs lift from |q_res,z| = 0.14 mm, and on the paper's optimum
next to it H = 3 stays within 0.33 % of H = 7 on every quantity read off the backbone
(docs/fidelity.md, docs/method_limits.md §2).
"""
from __future__ import annotations

import logging

import numpy as np

from ringdamper.nonlinear.fourier import Fourier

log = logging.getLogger(__name__)


def normal_force_ratio(backbone, contacts, nt: int = 256) -> np.ndarray:
    """``min_t N_p(t)/N0_p`` per grid amplitude and preloaded pair, ``(nα, n_preloaded)``, from the
    normal contact displacements ``backbone.d`` (slot layout of :mod:`ringdamper.nonlinear.fourier`,
    pair-major ``(n, t1, t2)`` coordinates), synthesised on ``nt`` samples per period; NaN where the
    backbone has no solution."""
    fourier = Fourier(backbone.H, nt)
    preloaded = np.flatnonzero(contacts.N0 > 0)
    d_normal = backbone.d[:, :, 3 * preloaded]                         # (nα, C, n_preloaded)
    samples = np.einsum("tc,acp->atp", fourier.E, d_normal)            # (nα, nt, n_preloaded)
    n0, kn = contacts.N0[preloaded], contacts.kn[preloaded]
    return np.min(1.0 + kn * samples / n0, axis=1)


def separation_indicators(backbone, contacts, usable: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(n_min, lifting)`` per amplitude: the smallest ratio of :func:`normal_force_ratio` over the
    preloaded pairs and the number of pairs with a ratio ≤ 0; NaN where not ``usable`` (and both
    NaN / 0 pairs when no pair is preloaded)."""
    ratio = normal_force_ratio(backbone, contacts)
    if ratio.shape[1] == 0:
        return np.full(len(usable), np.nan), np.where(usable, 0.0, np.nan)
    with np.errstate(invalid="ignore"):
        lifting = np.sum(ratio <= 0.0, axis=1).astype(float)
    return np.where(usable, ratio.min(axis=1), np.nan), np.where(usable, lifting, np.nan)


def warn_separation(lifting: np.ndarray, alpha: np.ndarray, n_harmonics: int) -> bool:
    """Log a warning if pairs lift off at some amplitude; True if they do."""
    opened = np.nan_to_num(lifting) > 0
    if not np.any(opened):
        return False
    first = int(np.argmax(opened))
    log.warning("contact pairs lift off during the period at %d amplitudes from alpha = %.4g (up to %d "
                "pairs): the clipped normal force feeds harmonics above H = %d, and with many pairs open "
                "the results there depend on H (docs/nonlinear_core.md §4.3)", int(opened.sum()),
                float(alpha[first]), int(np.nanmax(lifting)), n_harmonics)
    return True
