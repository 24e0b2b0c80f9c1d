"""The play operator (one-dimensional stop, hysteresis of a Jenkins element) and its periodic state
over one period (docs/nonlinear_core.md §2)."""
from __future__ import annotations

import numpy as np


def play_operator(lo: np.ndarray, hi: np.ndarray, w0: np.ndarray | float = 0.0):
    """Periodic steady state of the play operator ``w_k = clip(w_{k−1}, lo_k, hi_k)``.

    ``lo ≤ hi`` have shape ``(..., Nt)``, ``w0`` is the memory before the first period. Returns
    ``w`` and ``src`` (same shape): ``src = −1`` if ``w_k`` is the memory, ``s`` if it is ``lo_s``,
    ``Nt + s`` if it is ``hi_s``. Clamps compose as ``clip(clip(x, a1, b1), a2, b2) =
    clip(x, clip(a1, a2, b2), clip(b1, a2, b2))``; a Hillis–Steele scan builds the prefix maps.
    """
    nt = lo.shape[-1]
    a, b = lo.copy(), hi.copy()
    sa = np.broadcast_to(np.arange(nt), lo.shape).copy()
    sb = sa + nt
    step = 1
    while step < nt:
        ea, eb, esa, esb = a[..., :-step], b[..., :-step], sa[..., :-step], sb[..., :-step]
        la, lb, lsa, lsb = a[..., step:], b[..., step:], sa[..., step:], sb[..., step:]
        na, nsa = _clip_with_source(ea, esa, la, lb, lsa, lsb)
        nb, nsb = _clip_with_source(eb, esb, la, lb, lsa, lsb)
        a[..., step:], b[..., step:], sa[..., step:], sb[..., step:] = na, nb, nsa, nsb
        step *= 2
    w0 = np.broadcast_to(np.asarray(w0, float), lo.shape[:-1])
    start, s_start = _clip_with_source(w0, np.full(w0.shape, -1), a[..., -1], b[..., -1],
                                       sa[..., -1], sb[..., -1])
    w, src = _clip_with_source(start[..., None], s_start[..., None], a, b, sa, sb)
    if not np.array_equal(w[..., -1], start):       # one more period must reproduce the start
        raise RuntimeError("play operator: the marched state is not periodic")
    return w, src


def _clip_with_source(x, sx, lo, hi, slo, shi):
    """``clip(x, lo, hi)`` and its source. A tie goes to the bound: a value equal to a bound
    moves with it (the memory, source −1, is constant and would drop that derivative when the
    march restarts from its own periodic state)."""
    below, above = x <= lo, x >= hi
    return (np.where(below, lo, np.where(above, hi, x)),
            np.where(below, slo, np.where(above, shi, sx)))
