"""The play operator's periodic state (``ringdamper.nonlinear.contact.play``) against a march sample after sample,
with and without its sources, on random bounds with ties (values on a 0.1 grid, bounds that coincide)."""
import numpy as np
import pytest

from ringdamper.nonlinear.contact.play import play_operator


def _bounds(seed, nt):
    rng = np.random.default_rng(seed)
    centre = np.round(rng.standard_normal((6, 2, nt)), 1)
    radius = np.round(np.abs(rng.standard_normal((6, 2, nt))), 1)
    return centre - radius, centre + radius, np.round(rng.standard_normal((6, 2)), 1)


def _march(lo, hi, w0, periods=3):
    """``w_k = clip(w_{k−1}, lo_k, hi_k)`` sample after sample, the last of ``periods`` periods, and the
    sources the march takes (ties to the bound, the lower first; −1 the memory)."""
    nt = lo.shape[-1]
    w, src = np.array(w0, float), np.full(np.shape(w0), -1)
    values, sources = np.empty_like(lo), np.empty(lo.shape, int)
    for _ in range(periods):
        for k in range(nt):
            src = np.where(w <= lo[..., k], k, np.where(w >= hi[..., k], nt + k, src))
            w = np.clip(w, lo[..., k], hi[..., k])
            values[..., k], sources[..., k] = w, src
    return values, sources


@pytest.mark.parametrize("nt", [1, 7, 64])
def test_the_play_operator_is_the_march_with_its_sources(nt):
    lo, hi, w0 = _bounds(nt, nt)
    w, src = play_operator(lo, hi, w0)
    np.testing.assert_array_equal(w, _march(lo, hi, w0)[0])
    bound = np.where(src >= nt, np.take_along_axis(hi, src % nt, -1), np.take_along_axis(lo, src % nt, -1))
    np.testing.assert_array_equal(w, np.where(src < 0, w0[..., None], bound))
    values, none = play_operator(lo, hi, w0, sources=False)
    assert none is None
    np.testing.assert_array_equal(values, w)


def _tied_bounds(seed):
    """Bounds on a coarse grid (many ties), coinciding (a zero slip radius) over half the period in a
    third of the cases, or so wide in a fifth that the slider sticks at its memory."""
    rng = np.random.default_rng(seed)
    nt = int(rng.choice([1, 2, 3, 7, 8, 16, 64]))
    shape, grid = (int(rng.integers(1, 6)), 2, nt), rng.choice([0.1, 0.5, 1.0])
    centre = np.round(rng.standard_normal(shape) / grid) * grid
    radius = np.round(np.abs(rng.standard_normal(shape)) * rng.choice([0.0, 0.3, 1.0, 3.0]) / grid) * grid
    if seed % 3 == 0:
        radius[..., : nt // 2] = 0.0
    if seed % 5 == 0:
        radius += 10.0
    return centre - radius, centre + radius, np.round(rng.standard_normal(shape[:-1]) / grid) * grid


def test_the_sources_are_the_march_s_with_ties_to_the_bound():
    """On 400 random cases with ties, also where the bounds coincide: the lower bound's source on a tie,
    as the march takes it, and the memory's (−1) where the slider never reaches a bound."""
    stuck = 0
    for seed in range(400):
        lo, hi, w0 = _tied_bounds(seed)
        src = play_operator(lo, hi, w0)[1]
        np.testing.assert_array_equal(src, _march(lo, hi, w0)[1], err_msg=f"seed {seed}")
        stuck += int(np.any(src == -1))
    assert stuck >= 50
