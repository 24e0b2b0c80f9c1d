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
    The sources are the march's on the periodic values (``w_{−1} = w_{Nt−1}``): sample ``k`` takes its
    lower bound's where ``w_{k−1} ≤ lo_k``, else its upper bound's where ``w_{k−1} ≥ hi_k``, else the
    source of ``w_{k−1}``: that of the last such sample before ``k``, around the period, or the memory
    where no sample of the period reaches a bound. A tie goes to the bound (the memory, source −1, is
    constant and would drop that derivative when the march restarts from its own periodic state).
    Without ``sources`` only ``w`` is formed (``src`` None).
    """
    nt = lo.shape[-1]
    bounds = np.empty((2,) + lo.shape, np.result_type(lo, hi))   # (2, ..., Nt): the prefix maps' clamps
    bounds[0], bounds[1] = lo, hi
    step = 1
    while step < nt:
        bounds[..., step:] = _clamp(bounds[..., :-step], bounds[0, ..., step:], bounds[1, ..., step:])
        step *= 2
    a, b = bounds
    w0 = np.broadcast_to(np.asarray(w0, float), lo.shape[:-1])
    start = _clamp(w0, a[..., -1], b[..., -1])
    w = _clamp(start[..., None], a, b)
    if not np.array_equal(w[..., -1], start):       # one more period must reproduce the start
        raise RuntimeError("play operator: the marched state is not periodic")
    return w, (_sources(w, lo, hi) if sources else None)


def _clamp(x, lo, hi):
    """``clip(x, lo, hi) = min(max(x, lo), hi)`` as two ufuncs: the same values as ``np.clip``, without its
    layers of dispatch, which cost more than the arithmetic on the few pairs of a small system."""
    return np.minimum(np.maximum(x, lo), hi)


def _sources(w: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """Sources of the periodic play-operator values ``w`` (:func:`play_operator`): where the previous
    value reaches a bound (ties included), that bound's; elsewhere the last such sample's, carried
    forward around the period (a running maximum of the samples' indices); −1 where none is."""
    nt = w.shape[-1]
    previous = np.concatenate((w[..., -1:], w[..., :-1]), axis=-1)
    at_lo = previous <= lo
    k = np.arange(nt)
    code = np.where(at_lo, k, nt + k)
    last = np.maximum.accumulate(np.where(at_lo | (previous >= hi), k, -1), axis=-1)
    last = np.where(last >= 0, last, last[..., -1:])          # before the first: the period's last
    return np.where(last >= 0, np.take_along_axis(code, np.maximum(last, 0), axis=-1), -1)
