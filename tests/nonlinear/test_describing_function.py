"""1-DoF oscillator with one Jenkins element, H = 1: the EPMC backbone equals the
describing-function solution to 1e-8 at 20 amplitudes from full stick to gross slip.

The AFT error is O(Nt⁻²) (kinks of the hysteresis between samples); Nt = 2¹⁵ brings it below
1e-8 relative, and the solver tolerance is 1e-12.
"""
import numpy as np

from ringdamper.nonlinear.harmonic_balance.epmc import epmc
from ringdamper.status import Status

from .systems import describing_function, one_dof

M, KT, MU, N = 2.0, 50.0, 0.3, 10.0


def test_epmc_matches_describing_function():
    st, c = one_dof(H=1)
    a_s = MU * N / KT
    a = a_s * np.logspace(-1, 2, 20)                             # 0.1 a_s (stuck) … 100 a_s
    bb = epmc(st, c, np.sqrt(M) * a, H=1, nt=2 ** 15, tol=1e-12)
    assert np.all(bb.status == Status.CONVERGED)
    w, zeta = describing_function(a)
    assert np.max(np.abs(bb.omega / w - 1)) <= 1e-8
    stuck = a <= a_s
    assert np.all(bb.zeta[stuck] == 0.0) or np.max(np.abs(bb.zeta[stuck])) <= 1e-14
    assert np.max(np.abs(bb.zeta[~stuck] / zeta[~stuck] - 1)) <= 1e-8
    # the contact displacement amplitude is α/√m (mass normalisation of the fundamental)
    assert np.allclose(np.hypot(bb.d[:, 1, 1], bb.d[:, 2, 1]), a, rtol=1e-12)
