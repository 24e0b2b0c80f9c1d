"""Supernodal LDLᵀ block solves against dense LAPACK on sparse positive definite matrices."""
import numpy as np
import pytest
import scipy.sparse as sp

from ringdamper.fem.supernodal import SupernodalLDL


def _laplacian_3d(nx, ny, nz, block=None):
    """7-point Laplacian of an nx x ny x nz grid (Dirichlet), optionally kron a dense SPD block
    (three DoFs per node, like an elasticity matrix)."""
    def lap1(n):
        return sp.diags([-np.ones(n - 1), 2 * np.ones(n), -np.ones(n - 1)], [-1, 0, 1])
    eye = sp.identity
    A = (sp.kron(sp.kron(lap1(nx), eye(ny)), eye(nz)) + sp.kron(sp.kron(eye(nx), lap1(ny)), eye(nz))
         + sp.kron(sp.kron(eye(nx), eye(ny)), lap1(nz)))
    return sp.csc_matrix(A if block is None else sp.kron(A, block))


@pytest.fixture(scope="module")
def spd():
    block = np.array([[4.0, 1.0, 0.5], [1.0, 3.0, 0.2], [0.5, 0.2, 2.0]])
    return _laplacian_3d(9, 8, 7, block)


def test_block_solve_matches_dense(spd):
    rng = np.random.default_rng(1)
    B = rng.standard_normal((spd.shape[0], 37))
    factors = SupernodalLDL(spd)
    widths = [s.stop - s.start for s in factors.supernodes]
    assert max(widths) > 1 and len(widths) > 10          # the blocked path and the scatter are exercised
    X = factors.solve(B)
    exact = np.linalg.solve(spd.toarray(), B)
    assert np.abs(X - exact).max() <= 1e-12 * np.abs(exact).max()
    assert np.abs(spd @ X - B).max() <= 1e-12 * np.abs(B).max()


def test_single_column_and_superlu_agree(spd):
    b = np.random.default_rng(2).standard_normal((spd.shape[0], 1))
    factors = SupernodalLDL(spd)
    x_lu = factors.lu.solve(b[:, 0])
    assert np.abs(factors.solve(b)[:, 0] - x_lu).max() <= 1e-12 * np.abs(x_lu).max()


def test_indefinite_matrix_is_refused():
    A = _laplacian_3d(6, 5, 4) - 3.3 * sp.identity(120, format="csc")
    with pytest.raises(ValueError, match="not positive definite"):
        SupernodalLDL(A)


def test_block_shape_is_checked(spd):
    with pytest.raises(ValueError, match=r"B must be \(1512, k\), got \(1513,\)"):
        SupernodalLDL(spd).solve(np.ones(spd.shape[0] + 1))


def test_no_right_hand_side(spd):
    assert SupernodalLDL(spd).solve(np.zeros((spd.shape[0], 0))).shape == (spd.shape[0], 0)


def test_sparse_right_hand_side_is_the_dense_one(spd):
    """A sparse block B gives bit for bit the solve of B.toarray() (scattered, not densified)."""
    B = sp.random(spd.shape[0], 23, density=0.01, format="csr", random_state=3)
    factors = SupernodalLDL(spd)
    assert np.array_equal(factors.solve(B), factors.solve(B.toarray()))
