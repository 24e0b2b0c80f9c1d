"""The isotropic Coulomb slider's periodic state (``ringdamper.nonlinear.coulomb``).

* The linear cyclic recurrence ``x_k = A_k x_{k−1} + b_k`` (periodic) solved by the prefix scan is
  that recurrence, to 1e-12 of ``max|x|``.
* The trajectory is periodic: ``W_k = Φ_k(W_{k−1})`` with ``W_{−1} = W_{Nt−1}`` for every pair to 1e-12
  of the displacement scale, also where marching period after period does not settle in 500 periods.
* Where the march settles (one period changes the state and its derivatives by less than 1e-13), the
  states agree to 1e-11 of the displacement scale and the derivatives to 1e-8 of their largest entry.
  That is the march's own error: stopped by the change of one period, it is up to ``1e-13 λ/(1 − λ)``
  off the periodic state when a period contracts by ``λ`` close to 1 (measured on 120 random cases:
  ≤ 1.4e-12 and ≤ 3.2e-9; on the default ring's backbone states ≤ 4e-13 and ≤ 6e-12, ``make bench``,
  ``coulomb``). The derivatives against central differences: ``tests/nonlinear/test_jacobians.py``.
"""
import numpy as np
import pytest

from ringdamper.nonlinear.coulomb import _step_map, coulomb_slider, cyclic_affine, march
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


def test_cyclic_affine_solves_the_periodic_recurrence():
    rng = np.random.default_rng(0)
    A = 0.7 * rng.standard_normal((5, 64, 2, 2)) / np.sqrt(2)
    b = rng.standard_normal((5, 64, 2, 3))
    x, unique = cyclic_affine(A, b)
    assert unique.all()
    previous = np.roll(x, 1, axis=1)
    np.testing.assert_allclose(x, A @ previous + b, rtol=0, atol=1e-12 * np.max(np.abs(x)))


@pytest.mark.parametrize("amplitude", [0.5, 1.0, 2.0, 5.0, 30.0])
def test_the_slider_trajectory_is_periodic(amplitude):
    rate, E, d, r, closed = _states(amplitude, seed=int(10 * amplitude))
    W, _ = coulomb_slider(rate, E, d, r, closed, False, np.zeros((NPAIRS, 2)))
    after, _ = _step_map(np.roll(W, 1, axis=2), np.roll(d, 1, axis=2), d, r, [])
    scale = np.max(np.abs(d)) + np.max(r)
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
