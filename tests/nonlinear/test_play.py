"""The play operator's periodic state (``ringdamper.nonlinear.play``) against a march sample after sample,
with and without its sources, on random bounds with ties (values on a 0.1 grid)."""
import numpy as np
import pytest

from ringdamper.nonlinear.play import play_operator


def _bounds(seed, nt):
    rng = np.random.default_rng(seed)
    centre = np.round(rng.standard_normal((6, 2, nt)), 1)
    radius = np.round(np.abs(rng.standard_normal((6, 2, nt))), 1)
    return centre - radius, centre + radius, np.round(rng.standard_normal((6, 2)), 1)


def _march(lo, hi, w0, periods=3):
    """``w_k = clip(w_{k−1}, lo_k, hi_k)`` sample after sample, the last of ``periods`` periods."""
    w, out = np.array(w0, float), np.empty_like(lo)
    for _ in range(periods):
        for k in range(lo.shape[-1]):
            w = np.clip(w, lo[..., k], hi[..., k])
            out[..., k] = w
    return out


@pytest.mark.parametrize("nt", [1, 7, 64])
def test_the_play_operator_is_the_march_with_its_sources(nt):
    lo, hi, w0 = _bounds(nt, nt)
    w, src = play_operator(lo, hi, w0)
    np.testing.assert_array_equal(w, _march(lo, hi, w0))
    bound = np.where(src >= nt, np.take_along_axis(hi, src % nt, -1), np.take_along_axis(lo, src % nt, -1))
    np.testing.assert_array_equal(w, np.where(src < 0, w0[..., None], bound))
    values, none = play_operator(lo, hi, w0, sources=False)
    assert none is None
    np.testing.assert_array_equal(values, w)
