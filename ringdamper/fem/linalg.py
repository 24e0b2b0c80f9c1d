"""Sparse direct solves, the lowest modes of the symmetric/Hermitian FE matrices, and the complete
dense eigen-decomposition of a Hermitian pair restricted to a few rows of the eigenvectors.

:func:`factorize` is the one entry point of every sparse factorisation: SuperLU under a symmetric
fill-reducing ordering (:mod:`.ordering`; the minimum degree of A^T + A halves the fill of the
27-node-brick sector against SuperLU's default COLAMD and factorises ~2.5x faster), and for a real
positive definite matrix the supernodal LDL^T block solves of :mod:`.supernodal` on the same factors
(docs/investigations/2026-12-01-sparse-solver.md), for a complex Hermitian definite one on those of
its real equivalent (:class:`RealEquivalent`).
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
from scipy.linalg import lapack
from scipy.sparse.linalg import LinearOperator, eigsh

from .superlu import SymmetricLU
from .supernodal import SupernodalLDL

START_SEED = 0  # ARPACK's start vector: seeded, so that a rerun gives the same modes to the bit


def factorize(A: sp.spmatrix, definite: bool = False, ordering: str | None = None):
    """Factors of a structurally symmetric sparse matrix: ``.solve(b)`` = A⁻¹ b, b a vector or an
    (n, k) block.

    ``definite`` (A symmetric or Hermitian positive definite): every pivot on the diagonal, and for
    a real A the supernodal LDL^T factors whose block solves run level-3 BLAS
    (:class:`~.supernodal.SupernodalLDL`, which raises ``numpy.linalg.LinAlgError`` for a matrix
    that is not definite); otherwise SuperLU's threshold pivoting (any nonsingular A). ``ordering``
    is one of :data:`.ordering.ORDERINGS`, the measured default (:func:`.ordering.default_ordering`)
    if None.
    """
    if definite and not np.iscomplexobj(A):
        return SupernodalLDL(A, ordering)
    if definite:
        return RealEquivalent(A, ordering)
    return SymmetricLU(A, definite, ordering)


class RealEquivalent:
    """Factors of a complex Hermitian positive definite A = A_r + i A_i through its real symmetric
    positive definite equivalent R = [[A_r, -A_i], [A_i, A_r]] (A_i skew): A x = b is
    R [x_r; x_i] = [b_r; b_i], solved by the supernodal factors of R. SciPy's complex SuperLU
    factorises the 1x fixed part's ND-3 interior (4 371 rows) in 11 s, R (twice the rows) in 0.5 s."""

    def __init__(self, A: sp.spmatrix, ordering: str | None = None):
        self.n = A.shape[0]
        self.factors = SupernodalLDL(real_equivalent(A), ordering)

    @property
    def shape(self) -> tuple[int, int]:
        return (self.n, self.n)

    def solve(self, b: np.ndarray) -> np.ndarray:
        b = np.asarray(b)
        x = self.factors.solve(np.concatenate([b.real, b.imag]).astype(float))
        return x[:self.n] + 1j * x[self.n:]


def solve(A: sp.spmatrix, b: np.ndarray) -> np.ndarray:
    return factorize(A).solve(np.asarray(b, dtype=np.result_type(A.dtype, np.asarray(b).dtype)))


def start_vector(n: int, dtype) -> np.ndarray:
    """The Lanczos start vector: seeded normal entries (ARPACK's own is random at every call)."""
    return np.random.default_rng(START_SEED).standard_normal(n).astype(dtype)


def lowest_modes(K: sp.spmatrix, M: sp.spmatrix, n_modes: int, shift: float, lu=None):
    """(w^2, phi) of K phi = w^2 M phi nearest above ``shift``, ascending, phi mass-normalised.

    Shift-invert Lanczos written as the regular-inverse problem M phi = nu (K - s M) phi, whose
    largest nu = 1 / (w^2 - s) are the modes nearest above s (K - s M must be positive definite:
    s below the spectrum). ``lu`` holds factors of K - s M when the caller has them. This form, and
    not eigsh's ``sigma=`` with ``M=``, because the latter leaves for complex Hermitian matrices the
    matrices, the factors and the Krylov basis in a reference cycle inside SciPy's ARPACK wrapper,
    freed only when the garbage collector runs: memory then grows with every call.
    """
    dtype = np.result_type(K.dtype, M.dtype)
    shifted = (K - shift * M).tocsc()
    lu = factorize(shifted) if lu is None else lu
    inverse = LinearOperator(K.shape, matvec=lu.solve, dtype=dtype)
    nu, phi = eigsh(M, k=n_modes, M=shifted, Minv=inverse, which="LM",
                    v0=start_vector(K.shape[0], dtype))
    order = np.argsort(-nu)
    phi = phi[:, order]
    phi = phi / np.sqrt(np.real(np.einsum("ij,ij->j", phi.conj(), M @ phi)))
    return shift + 1.0 / nu[order], phi


def real_equivalent(A: sp.spmatrix) -> sp.csc_matrix:
    """[[A_r, -A_i], [A_i, A_r]]: real symmetric (definite) for a Hermitian (definite) A."""
    A = sp.csr_matrix(A)
    R = sp.bmat([[A.real, -A.imag], [A.imag, A.real]]).tocsc()
    R.eliminate_zeros()
    return R


def lowest_hermitian_modes(K: sp.spmatrix, M: sp.spmatrix, n_modes: int, lu: "RealEquivalent"):
    """(w^2, phi) of the lowest ``n_modes`` of a complex Hermitian pair (K definite), ascending, phi
    mass-normalised, by real Lanczos on the real equivalent pair (:func:`real_equivalent`): each
    eigenvalue of (K, M) is a double one of it, its real eigenspace {[Re c z; Im c z]}. The 2 n real
    vectors, read as complex z = x_r + i x_i, span the n complex modes; a Rayleigh–Ritz on them (M-
    orthonormalised, rank n) gives the modes themselves. ``lu``: factors of K's real equivalent."""
    KR, MR = real_equivalent(K), real_equivalent(M)
    w2, X = lowest_modes(KR, MR, 2 * n_modes, shift=0.0, lu=lu.factors)
    n = K.shape[0]
    Z = X[:n] + 1j * X[n:]
    g, U = np.linalg.eigh(Z.conj().T @ (M @ Z))
    Q = Z @ (U[:, -n_modes:] / np.sqrt(g[-n_modes:]))
    w2, V = sla.eigh(Q.conj().T @ (K @ Q))
    V = V / np.sqrt(np.real(np.einsum("ij,ij->j", V.conj(), V)))
    return w2, Q @ V


def eigh_rows(K: np.ndarray, M: np.ndarray, R: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """All eigenvalues w (ascending) of the dense Hermitian pair K phi = w M phi (M positive definite)
    and R Phi, the rows R (r x n, real or complex) of the mass-normalised eigenvectors Phi (Phi^H M Phi = I).

    The steps of LAPACK's ``zhegvd``/``dsygvd`` (what ``scipy.linalg.eigh(K, M)`` calls): M = L L^H
    (``potrf``), C = L^-1 K L^-H (``hegst``), C = Q T Q^H with T real tridiagonal (``hetrd``),
    T = Z diag(w) Z^T (divide and conquer, ``dstevd``: the ``dstedc`` that ``heevd`` runs), so
    Phi = L^-H Q Z and w are those of ``eigh`` to the bit. Only R Phi = ((R L^-H) Q) Z is formed: the
    Householder reflectors of Q are applied to the r rows of R L^-H (``unmqr``) instead of to the
    n x n matrix Z, and the last triangular solve has r right-hand sides instead of n.
    """
    cplx = np.iscomplexobj(K) or np.iscomplexobj(M) or np.iscomplexobj(R)
    dtype = np.complex128 if cplx else np.float64
    names = ("potrf", "hegst", "hetrd", "hetrd_lwork", "unmqr") if cplx else \
        ("potrf", "sygst", "sytrd", "sytrd_lwork", "ormqr")
    potrf, hegst, hetrd, hetrd_lwork, unmqr = lapack.get_lapack_funcs(names, dtype=dtype)
    n = K.shape[0]
    L, info = potrf(np.asarray(M, dtype=dtype), lower=1)
    if info:
        raise np.linalg.LinAlgError(f"M is not positive definite (potrf: leading minor {info})")
    C, info = hegst(np.asarray(K, dtype=dtype), L, itype=1, lower=1)
    work, info = hetrd_lwork(n, lower=1)
    reflectors, d, e, tau, info = hetrd(C, lower=1, lwork=int(work.real), overwrite_a=1)
    w, Z, info = lapack.dstevd(d, e, compute_v=1)
    if info:
        raise np.linalg.LinAlgError(f"the tridiagonal eigensolver did not converge (dstevd: {info})")
    # R L^-H = (L^-1 R^H)^H
    W = np.asfortranarray(sla.solve_triangular(L, np.asarray(R).conj().T.astype(dtype), lower=True).conj().T)
    if n > 1:   # Q = H(1) ... H(n-1) acts on coordinates 2..n (``unmtr`` with uplo L)
        W[:, 1:], _, info = unmqr("R", "N", reflectors[1:, :-1], tau[:n - 1], W[:, 1:],
                                  lwork=max(1, 64 * W.shape[0]), overwrite_c=1)
    rows = W.real @ Z
    if cplx:
        rows = rows + 1j * (W.imag @ Z)
    return w, rows
