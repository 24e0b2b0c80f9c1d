"""The isotropic Coulomb slider's periodic state (``ringdamper.nonlinear.contact.coulomb``).

* The linear cyclic recurrence ``x_k = A_k x_{k−1} + b_k`` (periodic) solved by the two-level scan is
  that recurrence, to 1e-12 of ``max|x|``, whatever the number of samples (blocks of any size).
* The step map's partial derivatives in closed form are the forward-mode derivatives of the march's
  sweep (:func:`tractrix_step`) to 1e-12 of their scale (1e-11 for ``∂Φ/∂c``: ``1/L`` for short
  segments), in every branch: slip, stick inside the disc, stick projected on it, a disc that does not
  move, separation.
* The trajectory is periodic: one period marched from ``W_{Nt−1}`` reproduces ``W`` for every pair to
  1e-12 of the displacement scale, also where marching period after period does not settle in 500
  periods.
* Where the march settles (one period changes the state and its derivatives by less than 1e-13), the
  states agree to 1e-11 of the displacement scale and the derivatives to 1e-8 of their largest entry.
  That is the march's own error: stopped by the change of one period, it is up to ``1e-13 λ/(1 − λ)``
  off the periodic state when a period contracts by ``λ`` close to 1 (measured on 120 random cases:
  ≤ 1.4e-12 and ≤ 3.2e-9; on the default ring's backbone states ≤ 4e-13 and ≤ 6e-12, ``make bench``,
  ``coulomb``). The derivatives against central differences: ``tests/nonlinear/test_jacobians.py``.
"""
import numpy as np
import pytest

from ringdamper.nonlinear.contact.coulomb import _Dual, _Segment, coulomb_slider, cyclic_affine, march, tractrix_step
from ringdamper.nonlinear.fourier import Fourier

NPAIRS = 40


def _states(amplitude, seed):
    """Tangential displacements, radii and contact states of ``NPAIRS`` random pairs (H = 3, Nt = 64)
    whose motion is ``amplitude`` times the slip radius, some opening over part of the period."""
    rng = np.random.default_rng(seed)
    fourier = Fourier(3, 64)
    kn, kt, mu, N0 = 1e5, 4e4, 0.3, 20.0
    radius = mu * N0 / kt
    d = rng.standard_normal((NPAIRS, 3, fourier.C)) * np.array([0.7 * N0 / kn, amplitude * radius,
                                                                 amplitude * radius])[None, :, None]
    d[:, :, 3:] *= 0.2
    dt = fourier.synth(d)
    N = N0 + kn * dt[:, 0]
    closed = N > 0
    rate = np.full(NPAIRS, mu * kn / kt)
    return rate, fourier.E, dt[:, 1:], mu * np.where(closed, N, 0.0) / kt, closed


@pytest.mark.parametrize("nt", [64, 20, 17, 1])
def test_cyclic_affine_solves_the_periodic_recurrence(nt):
    rng = np.random.default_rng(nt)
    A = 0.7 * rng.standard_normal((2, 2, nt, 5)) / np.sqrt(2)
    b = rng.standard_normal((2, nt, 3, 5))
    x, unique = cyclic_affine(A, b.copy())
    assert unique.all()
    after = np.einsum("ijkn,jkmn->ikmn", A, np.roll(x, 1, axis=1)) + b
    np.testing.assert_allclose(x, after, rtol=0, atol=1e-12 * np.max(np.abs(x)))


def _forward_mode(w, prev, cur, r):
    """The march's sweep :func:`tractrix_step` with forward-mode derivatives seeded on its seven inputs
    (``w``, ``c_{k−1}``, ``c_k`` (2 each), ``r``): ``(2, 7, n)``."""
    seeds = np.eye(7)
    inputs = [_Dual(v, np.broadcast_to(seeds[i], (v.size, 7))) for i, v in enumerate([*w, *prev, *cur, r])]
    out = tractrix_step(inputs[0:2], (*inputs[2:4], None), inputs[4:7])
    return np.stack([o.t.T for o in out])


def test_the_closed_form_partials_are_the_forward_mode_derivatives():
    rng = np.random.default_rng(7)
    n = 4000
    prev = rng.standard_normal((2, n))
    cur = prev + rng.standard_normal((2, n)) * rng.choice([0.05, 0.5, 2.0], n)
    cur[:, :100] = prev[:, :100]                                      # a disc that does not move
    r = rng.uniform(0.2, 1.5, n) * (rng.random(n) > 0.05)            # some separated (r = 0)
    w = prev + rng.standard_normal((2, n)) * rng.choice([0.3, 1.0, 3.0], n)
    step = _Segment(w, prev, cur, r)
    stuck, outside = ~step.slip & ~step.sep, np.hypot(*(w - prev)) > r
    for branch in (step.slip & outside, step.slip & ~outside, stuck & outside, stuck & ~outside, step.sep,
                   ~step.sep & np.all(cur == prev, axis=0)):
        assert branch.sum() >= 50
    D = _forward_mode(w, prev, cur, r)
    closed_form = {"w": (step.d_w(), D[:, 0:2], 1e-12), "c_k": (step.d_cur(), D[:, 4:6], 1e-11),
                   "c_(k-1)": (np.eye(2)[:, :, None] - step.d_w() - step.d_cur(), D[:, 2:4], 1e-11),
                   "r": (step.d_r(), D[:, 6], 1e-12)}
    for name, (mine, reference, tol) in closed_form.items():
        assert np.max(np.abs(mine - reference)) <= tol * max(1.0, np.max(np.abs(reference))), name


@pytest.mark.parametrize("amplitude", [0.5, 1.0, 2.0, 5.0, 30.0])
def test_the_slider_trajectory_is_periodic(amplitude):
    rate, E, d, r, closed = _states(amplitude, seed=int(10 * amplitude))
    W, _ = coulomb_slider(rate, E, d, r, closed, False, np.zeros((NPAIRS, 2)))
    scale = np.max(np.abs(d)) + np.max(r)
    after, _ = march(rate, E, d, r, closed, False, W[:, :, -1], scale, np.inf, 1)
    assert np.max(np.abs(after - W)) <= 1e-12 * scale


@pytest.mark.parametrize("amplitude", [0.5, 3.0, 10.0, 30.0])
def test_the_slider_is_the_settled_march(amplitude):
    rate, E, d, r, closed = _states(amplitude, seed=int(10 * amplitude))
    memory = np.zeros((NPAIRS, 2))
    scale = np.max(np.abs(d)) + np.max(r)
    W, dW = coulomb_slider(rate, E, d, r, closed, True, memory)
    W0, dW0 = march(rate, E, d, r, closed, True, memory, scale, 1e-13, 2000)
    assert np.max(np.abs(W - W0)) <= 1e-11 * scale
    assert np.max(np.abs(dW - dW0)) <= 1e-8 * np.max(np.abs(dW0))
