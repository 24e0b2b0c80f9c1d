"""The play operator (one-dimensional stop, hysteresis of a Jenkins element) and its periodic state
over one period (docs/nonlinear_core.md §2)."""
from __future__ import annotations

import numpy as np


def play_operator(lo: np.ndarray, hi: np.ndarray, w0: np.ndarray | float = 0.0, sources: bool = True):
    """Periodic steady state of the play operator ``w_k = clip(w_{k−1}, lo_k, hi_k)``.

    ``lo ≤ hi`` have shape ``(..., Nt)``, ``w0`` is the memory before the first period. Returns
    ``w`` and ``src`` (same shape): ``src = −1`` if ``w_k`` is the memory, ``s`` if it is ``lo_s``,
    ``Nt + s`` if it is ``hi_s``. Clamps compose as ``clip(clip(x, a1, b1), a2, b2) =
    clip(x, clip(a1, a2, b2), clip(b1, a2, b2))``; a Hillis–Steele scan builds the prefix maps, the
    lower and upper bounds stacked on one leading axis so that each doubling step clamps both at once.
    A tie goes to the bound: a value equal to a bound takes that bound's source (the memory, source
    −1, is constant and would drop that derivative when the march restarts from its own periodic
    state). Without ``sources`` only ``w`` is formed (``src`` None).
    """
    nt = lo.shape[-1]
    bounds = np.empty((2,) + lo.shape, np.result_type(lo, hi))   # (2, ..., Nt): the prefix maps' clamps
    bounds[0], bounds[1] = lo, hi
    if sources:
        src = np.empty((2,) + lo.shape, int)
        src[0], src[1] = np.arange(nt), np.arange(nt, 2 * nt)
    step = 1
    while step < nt:
        early, a, b = bounds[..., :-step], bounds[0, ..., step:], bounds[1, ..., step:]
        if sources:
            src[..., step:] = _source(early, a, b, src[..., :-step], src[0, ..., step:], src[1, ..., step:])
        bounds[..., step:] = _clamp(early, a, b)
        step *= 2
    a, b = bounds
    w0 = np.broadcast_to(np.asarray(w0, float), lo.shape[:-1])
    start = _clamp(w0, a[..., -1], b[..., -1])
    w = _clamp(start[..., None], a, b)
    if not np.array_equal(w[..., -1], start):       # one more period must reproduce the start
        raise RuntimeError("play operator: the marched state is not periodic")
    if not sources:
        return w, None
    start_source = _source(w0, a[..., -1], b[..., -1], -1, src[0, ..., -1], src[1, ..., -1])
    return w, _source(start[..., None], a, b, start_source[..., None], src[0], src[1])


def _clamp(x, lo, hi):
    """``clip(x, lo, hi) = min(max(x, lo), hi)`` as two ufuncs: the same values as ``np.clip``, without its
    layers of dispatch, which cost more than the arithmetic on the few pairs of a small system."""
    return np.minimum(np.maximum(x, lo), hi)


def _source(x, lo, hi, x_source, lo_source, hi_source):
    """Source of ``clip(x, lo, hi)``: the bound's where ``x`` reaches it (ties included), else ``x``'s."""
    return np.where(x <= lo, lo_source, np.where(x >= hi, hi_source, x_source))
