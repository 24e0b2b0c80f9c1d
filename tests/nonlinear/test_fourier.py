"""Fourier/AFT operators: exactness and the complex ↔ real-slot conventions."""
import numpy as np

from ringdamper.nonlinear.fourier import Fourier, real_block, real_vector, to_complex, to_real


def test_analysis_inverts_synthesis_for_minimal_nt():
    for H, nt in [(1, 3), (3, 7), (5, 16)]:
        f = Fourier(H, nt)
        assert np.allclose(f.F @ f.E, np.eye(2 * H + 1), atol=1e-13)


def test_complex_convention_and_real_forms():
    rng = np.random.default_rng(1)
    H, f = 3, Fourier(3, 32)
    c = rng.standard_normal((2 * H + 1, 4))
    X = to_complex(c, H)
    x = f.synth(c.T)                                     # (4, nt)
    recon = np.real(np.exp(1j * np.outer(f.tau, np.arange(H + 1))) @ X).T
    assert np.allclose(x, recon, atol=1e-13)
    assert np.allclose(to_real(X), c)
    A = rng.standard_normal((4, 4)) + 1j * rng.standard_normal((4, 4))
    v = X[2]
    assert np.allclose(real_block(A) @ real_vector(v), real_vector(A @ v))
