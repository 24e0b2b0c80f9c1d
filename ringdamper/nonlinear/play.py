"""The play operator (one-dimensional stop, hysteresis of a Jenkins element) and its periodic state
over one period (docs/nonlinear_core.md §2)."""
from __future__ import annotations

import numpy as np


def play_operator(lo: np.ndarray, hi: np.ndarray, w0: np.ndarray | float = 0.0, sources: bool = True):
    """Periodic steady state of the play operator ``w_k = clip(w_{k−1}, lo_k, hi_k)``.

    ``lo ≤ hi`` have shape ``(..., Nt)``, ``w0`` is the memory before the first period. Returns
    ``w`` and ``src`` (same shape): ``src = −1`` if ``w_k`` is the memory, ``s`` if it is ``lo_s``,
    ``Nt + s`` if it is ``hi_s``. Clamps compose as ``clip(clip(x, a1, b1), a2, b2) =
    clip(x, clip(a1, a2, b2), clip(b1, a2, b2))``; a Hillis–Steele scan builds the prefix maps.
    Without ``sources`` only ``w`` is formed (``src`` None), by plain clips.
    """
    nt = lo.shape[-1]
    index = [np.broadcast_to(np.arange(nt), lo.shape)] if sources else []
    a = [lo.copy()] + [i.copy() for i in index]                  # lower bounds (and their sources)
    b = [hi.copy()] + [i + nt for i in index]                    # upper bounds
    step = 1
    while step < nt:
        late_a, late_b = [x[..., step:] for x in a], [x[..., step:] for x in b]
        new_a = _clip_with_source([x[..., :-step] for x in a], late_a, late_b)
        new_b = _clip_with_source([x[..., :-step] for x in b], late_a, late_b)
        for x, y in zip(late_a + late_b, new_a + new_b):
            x[...] = y
        step *= 2
    w0 = np.broadcast_to(np.asarray(w0, float), lo.shape[:-1])
    start = _clip_with_source([w0] + ([np.full(w0.shape, -1)] if sources else []), [x[..., -1] for x in a],
                              [x[..., -1] for x in b])
    w = _clip_with_source([x[..., None] for x in start], a, b)
    if not np.array_equal(w[0][..., -1], start[0]):       # one more period must reproduce the start
        raise RuntimeError("play operator: the marched state is not periodic")
    return w[0], (w[1] if sources else None)


def _clip_with_source(x, lo, hi):
    """``clip(x, lo, hi)`` and its source, each given as ``[value, source]`` (``[value]``: the clip
    alone). A tie goes to the bound: a value equal to a bound moves with it (the memory, source −1, is
    constant and would drop that derivative when the march restarts from its own periodic state)."""
    if len(x) == 1:
        return [np.clip(x[0], lo[0], hi[0])]
    below, above = x[0] <= lo[0], x[0] >= hi[0]
    return [np.where(below, lo[i], np.where(above, hi[i], x[i])) for i in range(2)]
