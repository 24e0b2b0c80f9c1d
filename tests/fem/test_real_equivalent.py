"""Complex Hermitian definite solves and modes through the real equivalent (fem.linalg): the same
solutions and lowest eigenpairs as dense LAPACK, to round-off, on a complex Hermitian pair of the
sparsity of a cyclically projected FE matrix (a 3-D Laplacian with a skew imaginary coupling)."""
import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp

from ringdamper.fem.linalg import RealEquivalent, factorize, lowest_hermitian_modes


def _pair(n_side=8, seed=0):
    rng = np.random.default_rng(seed)
    d = sp.diags([-1.0, 2.0, -1.0], [-1, 0, 1], shape=(n_side, n_side))
    eye = sp.identity(n_side)
    lap = (sp.kron(sp.kron(d, eye), eye) + sp.kron(sp.kron(eye, d), eye) + sp.kron(sp.kron(eye, eye), d))
    upper = sp.triu(sp.random(lap.shape[0], lap.shape[0], density=0.01, random_state=seed), 1)
    skew = 0.3 * (upper - upper.T)
    K = (lap + 1j * skew + 0.5 * sp.identity(lap.shape[0])).tocsr()
    M = sp.diags(1.0 + rng.random(lap.shape[0])).tocsr().astype(complex)
    return K, M


def test_solves_equal_dense_lapack():
    K, _ = _pair()
    factors = factorize(K, definite=True)
    assert isinstance(factors, RealEquivalent)
    b = np.random.default_rng(1).standard_normal((K.shape[0], 5)) * (1 + 1j)
    np.testing.assert_allclose(factors.solve(b), np.linalg.solve(K.toarray(), b), rtol=0, atol=1e-12)


def test_lowest_modes_equal_dense_lapack():
    K, M = _pair()
    w2, phi = lowest_hermitian_modes(K, M, 12, factorize(K, definite=True))
    ref = sla.eigh(K.toarray(), M.toarray(), eigvals_only=True, subset_by_index=(0, 11))
    np.testing.assert_allclose(w2, ref, rtol=1e-10)
    np.testing.assert_allclose(phi.conj().T @ (M @ phi), np.eye(12), atol=1e-10)
    np.testing.assert_allclose(K @ phi, (M @ phi) * w2, atol=1e-9)
