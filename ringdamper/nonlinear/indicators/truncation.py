"""Harmonic-truncation indicator of a harmonic-balance solution (docs/method_limits.md §2).

With mass-normalised modes of every harmonic, the time-mean mechanical energy carried by harmonic
``h ≥ 1`` of ``q(t) = Re Σ_h Φ_h η_h e^{ihωt}`` is

    E_h = ¼ Σ_r (ω_r² + (hω)²) |η_{h,r}|²       (kinetic ¼(hω)²|η|² plus potential ¼ω_r²|η|²),

and the indicator is the fraction ``ε_H = E_H / Σ_{h=1..H} E_h`` in the highest retained harmonic.
Harmonic-balance coefficients of a piecewise-linear contact decay like a power of ``h``; a solution
whose last harmonic still holds a sizeable share of the energy has not converged in H. At H = 1 the
fraction is 1 by definition and says nothing: the indicator is NaN there (check one case at H ≥ 2).
Above ``THRESHOLD`` a warning names the amplitudes concerned.
"""
from __future__ import annotations

import logging

import numpy as np

log = logging.getLogger(__name__)

#: ε_H above which the truncation is reported (docs/method_limits.md §2: on the separating-contact
#: study every solution with ε_H below 3.5e-4 is within 1 % of the converged ω and amplitude at
#: equal forcing; the default ring at H = 3 stays below 6e-5)
THRESHOLD = 3e-4


def highest_harmonic_fraction(modal: list, eta: list, omega) -> np.ndarray:
    """ε_H per point: ``modal[h]`` the structure's modal data of harmonic h (``w2``), ``eta[h]``
    the modal coordinates ``(points, m_h)`` and ``omega`` (points,) [rad/s]; NaN at H = 1 or where
    ω is not finite."""
    H = len(eta) - 1
    omega = np.asarray(omega, float)
    if H < 2:
        return np.full(omega.shape, np.nan)
    energy = np.stack([0.25 * np.sum((modal[h].w2 + (h * omega[:, None]) ** 2)
                                      * np.abs(eta[h]) ** 2, axis=1) for h in range(1, H + 1)])
    with np.errstate(invalid="ignore", divide="ignore"):
        return energy[-1] / energy.sum(axis=0)


def warn_truncation(fraction: np.ndarray, alpha: np.ndarray, threshold: float = THRESHOLD) -> bool:
    """Log a warning if ``fraction`` exceeds ``threshold`` anywhere; True if it did."""
    high = fraction > threshold
    if not np.any(high):
        return False
    log.warning("the highest harmonic holds up to %.2g of the vibration energy (> %.2g) at %d "
                "amplitudes from alpha = %.4g: more harmonics are needed there", np.nanmax(fraction),
                threshold, int(high.sum()), float(alpha[np.argmax(high)]))
    return True
