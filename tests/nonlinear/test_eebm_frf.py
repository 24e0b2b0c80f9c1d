"""E-EBM against the forced response on the 1-DoF Jenkins oscillator, H = 1.

With friction-only damping the E-EBM is exact: the forcing it predicts at the FRF's peak
amplitude equals the FRF's forcing. With structural damping ζs the forced peak sits slightly off
the backbone and the E-EBM over-predicts the forcing by ≈ ζ²/2, ζ = c/(2mω₀) the structural
damping ratio at the nonlinear resonance (exactly
``(k_i + cω₀) / min_Ω |k + k_r − mΩ² + i(k_i + cΩ)|`` for the describing function).
"""
import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from ringdamper.nonlinear.harmonic_balance.eebm import eebm
from ringdamper.nonlinear.harmonic_balance.epmc import epmc
from ringdamper.nonlinear.harmonic_balance.frf import forced_response, resonance_peak
from ringdamper.status import Status

from .systems import one_dof

M, K, KT, MU, N = 2.0, 100.0, 50.0, 0.3, 10.0
NT = 4096


def eebm_at(a, zeta_s):
    st, c = one_dof(H=1)
    bb = epmc(st, c, np.array([np.sqrt(M) * a]), H=1, nt=NT, tol=1e-12)
    assert bb.status[0] == Status.CONVERGED
    return eebm(bb, zeta_s=zeta_s)


def describing_function_ratio(a, zeta_s):
    """Exact (H = 1) ratio E-EBM forcing / forcing whose FRF peak has amplitude ``a``."""
    a_s = MU * N / KT
    beta = np.arccos(1 - 2 * a_s / a)
    kr = KT / np.pi * (beta - 0.5 * np.sin(2 * beta))
    ki = 4 * MU * N * (a - a_s) / (np.pi * a * a)
    c = 2 * zeta_s * np.sqrt(K * M)
    w0 = np.sqrt((K + kr) / M)
    g = minimize_scalar(lambda W: np.hypot(K + kr - M * W * W, ki + c * W),
                        bounds=(0.9 * w0, 1.1 * w0), method="bounded",
                        options={"xatol": 1e-12}).fun
    return (ki + c * w0) / g


@pytest.mark.parametrize("zeta_s", [0.0, 0.02])
def test_eebm_forcing_matches_frf_peak(zeta_s):
    a_star = 3.0 * MU * N / KT
    pred = eebm_at(a_star, zeta_s)
    gamma, w0 = pred.gamma[0], pred.omega[0]
    assert pred.q_res_h1[0] == pytest.approx(a_star, rel=1e-12)
    assert pred.phi[0] == pytest.approx(np.pi / 2, abs=1e-12)     # force in phase with velocity
    st, c = one_dof(H=1)
    frf = forced_response(st, c, gamma, 0.95 * w0, 1.05 * w0, H=1, nt=NT, zeta_s=zeta_s,
                          tol=1e-12)
    assert frf.status == Status.CONVERGED
    peak = resonance_peak(frf, measure="h1")
    assert peak.refined
    back = eebm_at(peak.q_h1, zeta_s)                  # E-EBM forcing at the FRF's peak amplitude
    ratio = back.gamma[0] / gamma
    if zeta_s == 0.0:
        assert ratio == pytest.approx(1.0, abs=1e-6)
        assert peak.omega == pytest.approx(w0, rel=1e-4)
    else:
        zeta_eff = zeta_s * np.sqrt(K / M) / peak.omega     # structural damping at the resonance
        assert ratio - 1 == pytest.approx(zeta_eff ** 2 / 2, rel=0.02)
        assert ratio == pytest.approx(describing_function_ratio(peak.q_h1, zeta_s), abs=1e-6)
    # E_f(γ, φ) = E_damp: forcing work π γ |Q_1ᴴ F̂| with F̂ = 1 on the only DoF, |Q_1| = a*
    assert pred.e_damp[0] == pytest.approx(np.pi * gamma * a_star, rel=1e-12)
