"""Fourier operators of the harmonic balance (real cosine/sine unknowns, AFT sampling).

Convention used everywhere in :mod:`ringdamper.nonlinear` (docs/nonlinear_core.md §1)::

    x(τ) = c_0 + Σ_{h=1..H} [ c_{2h-1} cos(hτ) + c_{2h} sin(hτ) ],      τ = ω t,
    X_0 = c_0,   X_h = c_{2h-1} − i c_{2h}   ⇒   x(τ) = Re Σ_{h=0..H} X_h e^{ihτ},

so that d/dt ↔ i h ω X_h. The ``C = 2H + 1`` real coefficients of one signal are its *slots*;
harmonic ``h ≥ 1`` owns slots ``(2h-1, 2h)``. The AFT samples ``τ_k = 2πk/Nt``, k = 0..Nt−1, and
the discrete transform is exact for trigonometric polynomials of degree ≤ H when Nt ≥ 2H + 1.

A complex-linear map ``Y = A X`` acting on ``(a, b)`` with ``X = a − ib`` is, in real slots,
``[[Re A, Im A], [−Im A, Re A]]`` (:func:`real_block`).
"""
from __future__ import annotations

import numpy as np


class Fourier:
    """Synthesis/analysis matrices for H harmonics sampled at Nt points per period.

    ``E`` (Nt × C) maps coefficients to samples, ``F`` (C × Nt) samples to coefficients (its
    left inverse, ``F @ E = I``), ``dE`` (Nt × C) coefficients to the samples of the derivative in τ
    (velocities are ``ω · dE c``).
    """

    def __init__(self, H: int, nt: int):
        if H < 0 or nt < 2 * H + 1:
            raise ValueError(f"need H >= 0 and Nt >= 2H+1 (got H={H}, Nt={nt})")
        self.H, self.nt, self.C = int(H), int(nt), 2 * int(H) + 1
        self.tau = 2.0 * np.pi * np.arange(nt) / nt
        h = np.arange(1, H + 1)
        E = np.ones((nt, self.C))
        E[:, 1::2] = np.cos(np.outer(self.tau, h))
        E[:, 2::2] = np.sin(np.outer(self.tau, h))
        self.E = E
        dE = np.zeros((nt, self.C))
        dE[:, 1::2] = -h * np.sin(np.outer(self.tau, h))
        dE[:, 2::2] = h * np.cos(np.outer(self.tau, h))
        self.dE = dE
        self.F = E.T * (2.0 / nt)
        self.F[0] /= 2.0

    def synth(self, c: np.ndarray) -> np.ndarray:
        """Coefficients ``(..., C)`` → samples ``(..., Nt)``."""
        return c @ self.E.T

    def analyse(self, x: np.ndarray) -> np.ndarray:
        """Samples ``(..., Nt)`` → coefficients ``(..., C)``."""
        return x @ self.F.T

    def slots(self, h: int) -> slice:
        """Slots of harmonic ``h`` (``[0]`` for h = 0, ``[2h-1, 2h]`` otherwise)."""
        return slice(0, 1) if h == 0 else slice(2 * h - 1, 2 * h + 1)


def default_nt(H: int) -> int:
    """Default AFT sample count: a power of two ≥ max(32, 16 H) (a dial of docs/design.md §6)."""
    return int(2 ** np.ceil(np.log2(max(32, 16 * H))))


def to_complex(c: np.ndarray, H: int) -> np.ndarray:
    """Real slots on the first axis ``(C, ...)`` → complex harmonics ``(H+1, ...)``."""
    X = np.empty((H + 1,) + c.shape[1:], dtype=complex)
    X[0] = c[0]
    X[1:] = c[1::2] - 1j * c[2::2]
    return X


def to_real(X: np.ndarray) -> np.ndarray:
    """Complex harmonics ``(H+1, ...)`` → real slots ``(C, ...)`` (imaginary part of X_0 dropped)."""
    H = X.shape[0] - 1
    c = np.empty((2 * H + 1,) + X.shape[1:])
    c[0] = X[0].real
    c[1::2] = X[1:].real
    c[2::2] = -X[1:].imag
    return c


def real_block(A: np.ndarray) -> np.ndarray:
    """Real form of ``Y = A X`` on ``(a; b)`` slots, ``X = a − ib``: ``[[Ar, Ai], [−Ai, Ar]]``."""
    Ar, Ai = A.real, A.imag
    m, n = A.shape
    out = np.empty((2 * m, 2 * n), Ar.dtype)
    out[:m, :n], out[:m, n:], out[m:, :n], out[m:, n:] = Ar, Ai, -Ai, Ar
    return out


def real_vector(v: np.ndarray) -> np.ndarray:
    """Complex vector ``v`` → its ``(a; b)`` slots, ``v = a − ib``."""
    return np.concatenate([v.real, -v.imag])
