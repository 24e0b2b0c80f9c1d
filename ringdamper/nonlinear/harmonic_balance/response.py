"""Response DoF of a condensed solution: its harmonics and the peak of its time signal."""
from __future__ import annotations

import numpy as np


def response_harmonics(modal: list, eta: list) -> np.ndarray:
    """``q_res,h = r_h · Q_h = (r_h Φ_h) η_h`` for ``h = 0..H`` (complex, convention of
    :mod:`ringdamper.nonlinear.fourier`)."""
    return np.array([m.res @ e for m, e in zip(modal, eta)])


def time_peak(q: np.ndarray, samples_per_harmonic: int = 64, iterations: int = 8) -> float:
    """``max_τ |Re Σ_h q_h e^{ihτ}|``: best of a fine grid, polished by Newton on the derivative."""
    H = q.size - 1
    h = np.arange(H + 1)
    n = samples_per_harmonic * max(H, 1)
    tau = 2 * np.pi * np.arange(n) / n
    x = np.real(np.exp(1j * np.outer(tau, h)) @ q)
    k = int(np.argmax(np.abs(x)))
    t = tau[k]
    best = abs(x[k])
    for _ in range(iterations):
        e = np.exp(1j * h * t)
        d1 = np.real(1j * h * q @ e)
        d2 = np.real(-(h ** 2) * q @ e)
        if d2 == 0:
            break
        t_new = t - d1 / d2
        if abs(t_new - t) > 2 * np.pi / n:          # stay in the grid cell of the maximum
            break
        t = t_new
        best = max(best, abs(np.real(q @ np.exp(1j * h * t))))
    return float(best)
