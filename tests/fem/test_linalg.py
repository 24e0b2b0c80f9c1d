"""Dense Hermitian eigen-decomposition restricted to rows (fem.linalg.eigh_rows) against scipy's eigh."""
import numpy as np
import pytest
import scipy.linalg as sla

from ringdamper.fem.linalg import eigh_rows


def _pair(n: int, complex_: bool, seed: int):
    rng = np.random.default_rng(seed)
    A = rng.standard_normal((n, n)) + (1j * rng.standard_normal((n, n)) if complex_ else 0)
    B = rng.standard_normal((n, n)) + (1j * rng.standard_normal((n, n)) if complex_ else 0)
    K = A @ A.conj().T
    K = 0.5 * (K + K.conj().T)                  # Hermitian positive semi-definite
    M = B @ B.conj().T + n * np.eye(n)
    return K, M, rng.standard_normal((7, n))


@pytest.mark.parametrize("complex_", [False, True])
def test_eigenvalues_bitwise_and_rows_of_mass_normalised_modes(complex_):
    """Eigenvalues identical to eigh's (the same LAPACK steps); R Phi equal to R times eigh's Phi up
    to each mode's sign or phase, within 1e-10 of the row's size."""
    K, M, R = _pair(120, complex_, seed=4)
    w_ref, phi = sla.eigh(K, M)
    w, rows = eigh_rows(K, M, R)
    assert np.array_equal(w, w_ref)
    ref = R @ phi
    phase = np.einsum("ij,ij->j", ref.conj(), rows)
    phase /= np.abs(phase)
    assert np.abs(rows / phase - ref).max() <= 1e-10 * np.abs(ref).max()
    assert np.iscomplexobj(rows) == complex_


def test_complex_rows_of_a_complex_pair():
    """Complex rows (the contact operator of a travelling-wave harmonic): R Phi as above."""
    K, M, R = _pair(60, True, seed=6)
    R = R + 1j * np.random.default_rng(7).standard_normal(R.shape)
    w_ref, phi = sla.eigh(K, M)
    w, rows = eigh_rows(K, M, R)
    ref = R @ phi
    phase = np.einsum("ij,ij->j", ref.conj(), rows)
    phase /= np.abs(phase)
    assert np.abs(rows / phase - ref).max() <= 1e-10 * np.abs(ref).max()


def test_not_positive_definite_mass_is_refused():
    K, M, R = _pair(10, False, seed=5)
    with pytest.raises(np.linalg.LinAlgError, match="not positive definite"):
        eigh_rows(K, -M, R)
