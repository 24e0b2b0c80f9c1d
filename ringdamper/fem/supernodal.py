"""Sparse LDLᵀ factors of a symmetric positive definite matrix, solved for many right-hand sides at once.

SuperLU (:class:`~ringdamper.fem.superlu.SymmetricLU`, ``definite``) with a symmetric fill-reducing
ordering and diagonal pivoting (no row interchanges, stable for a positive definite matrix) factorises

    P A Pᵀ = L U,   U = D Lᵀ (to round-off),   D = diag(U),

so A⁻¹ = Pᵀ L⁻ᵀ D⁻¹ L⁻¹ P. The columns of L come in supernodes: runs of consecutive columns
c0..c1-1 whose structure below the diagonal block is the same row set R. Per supernode the forward
solve L y = b is one dense unit-triangular solve with the diagonal block and one product with the
rows R,

    y[c0:c1] = L[c0:c1, c0:c1]⁻¹ y[c0:c1],   y[R] -= L[R, c0:c1] y[c0:c1],

and the backward solve Lᵀ x = D⁻¹ y runs the transposed steps in reverse order. With k right-hand
sides these are level-3 BLAS calls (trsm, gemm) on k columns at once; SuperLU's own solve, as SciPy
builds it, runs its triangular solves one right-hand side at a time. The same SuperLU object still
serves single-vector solves (``solve(b)`` of a vector is ``lu.solve``), e.g. inside a Lanczos iteration.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from scipy.linalg.blas import dgemm, dtrsm

from .superlu import SymmetricLU

#: Columns per chunk of the final un-permutation: a chunk-sized buffer instead of a second copy of X.
UNPERMUTE_COLUMNS = 64


def _into(target: np.ndarray, result: np.ndarray) -> None:
    """Store a BLAS result in ``target`` unless BLAS already wrote it there (Fortran-ordered views are
    updated in place; a copy is made only if the wrapper had to copy its argument)."""
    if not np.shares_memory(result, target):
        target[...] = result


@dataclass
class Supernode:
    start: int               # first column c0
    stop: int                # one past the last column c1
    below: np.ndarray        # row set R (sorted, all >= stop)
    diagonal: np.ndarray     # L[c0:c1, c0:c1], unit lower triangular, Fortran order
    rows_below: np.ndarray   # L[R, c0:c1], C order


def _supernode_starts(L: sp.csc_matrix) -> np.ndarray:
    """First column of every fundamental supernode, and n: column j + 1 continues the supernode of
    column j when its structure is that of column j without its diagonal row j."""
    ind, ptr = L.indices, L.indptr
    n = L.shape[0]
    count = np.diff(ptr)
    col = np.repeat(np.arange(n), count)
    # entry q of column c >= 1 against entry q - ptr[c] + 1 of column c - 1 (where the counts fit)
    fits = np.zeros(n, dtype=bool)
    fits[1:] = count[:-1] == count[1:] + 1
    q = np.flatnonzero(fits[col])
    partner = q - ptr[col[q]] + ptr[col[q] - 1] + 1
    differs = np.zeros(n, dtype=bool)
    differs[col[q[ind[q] != ind[partner]]]] = True
    joins = fits & ~differs
    joins[0] = False
    return np.append(np.flatnonzero(~joins), n)


def _supernodes(L: sp.csc_matrix) -> list[Supernode]:
    """The fundamental supernodes of a CSC lower-triangular factor with its diagonal stored."""
    ind, ptr, val = L.indices, L.indptr, L.data
    starts = _supernode_starts(L)
    out = []
    for c0, c1 in zip(starts[:-1].tolist(), starts[1:].tolist()):
        w = c1 - c0
        rows = ind[ptr[c0]:ptr[c0 + 1]]
        if not np.array_equal(rows[:w], np.arange(c0, c1)):
            raise ValueError("the factor's columns must be sorted with the diagonal stored")
        block = np.zeros((len(rows), w))
        for j in range(c0, c1):
            block[j - c0:, j - c0] = val[ptr[j]:ptr[j + 1]]
        out.append(Supernode(start=c0, stop=c1, below=rows[w:],
                             diagonal=np.asfortranarray(block[:w]), rows_below=np.ascontiguousarray(block[w:])))
    return out


class SupernodalLDL:
    """LDLᵀ factors of a real symmetric positive definite sparse matrix; ``solve(B)`` for a block B."""

    def __init__(self, A: sp.spmatrix, ordering: str | None = None):
        self.lu = SymmetricLU(A, definite=True, ordering=ordering)
        if not np.array_equal(self.lu.lu.perm_r, self.lu.lu.perm_c):
            raise np.linalg.LinAlgError("SuperLU interchanged rows: the matrix is not positive definite")
        self.perm = self.lu.perm
        self.d = self.lu.lu.U.diagonal()
        if np.any(self.d <= 0):
            raise np.linalg.LinAlgError("the matrix is not positive definite (a pivot is <= 0)")
        self.supernodes = _supernodes(self.lu.lu.L.tocsc())

    @property
    def shape(self) -> tuple[int, int]:
        return self.lu.shape

    def solve(self, B) -> np.ndarray:
        """A⁻¹ B for a real (n, k) block B, dense or sparse (a sparse B is scattered straight into the
        permuted work array: no dense copy of it is made); a vector is SuperLU's single solve."""
        if not sp.issparse(B):
            B = np.asarray(B, dtype=float)
            if B.shape == (self.shape[0],):
                return self.lu.solve(B)
        if B.ndim != 2 or B.shape[0] != self.shape[0]:
            raise ValueError(f"B must be ({self.shape[0]}, k), got {B.shape}")
        if sp.issparse(B):
            B = B.tocoo()
            X = np.zeros(B.shape, dtype=float)
            X[self.perm[B.row], B.col] = B.data    # P B (row i of B goes to position perm[i])
        else:
            X = np.empty(B.shape, dtype=float)
            X[self.perm] = B
        if B.shape[1]:
            self._solve_permuted(X)
        for c in range(0, X.shape[1], UNPERMUTE_COLUMNS):    # X <- Pᵀ X, in place by column chunks
            X[:, c:c + UNPERMUTE_COLUMNS] = X[self.perm, c:c + UNPERMUTE_COLUMNS]
        return X

    def _solve_permuted(self, X: np.ndarray) -> None:
        """X <- (P A Pᵀ)⁻¹ X in place, for a C-ordered (n, k) X already in the permuted order."""
        # X is C-ordered: X[c0:c1].T is a Fortran-ordered view, which BLAS updates in place
        for s in self.supernodes:         # L y = P B
            xs = X[s.start:s.stop].T
            _into(xs, dtrsm(1.0, s.diagonal, xs, side=1, lower=1, trans_a=1, diag=1, overwrite_b=1))
            if len(s.below):
                X[s.below] -= (xs @ s.rows_below.T).T
        X /= self.d[:, None]
        for s in reversed(self.supernodes):   # Lᵀ x = D⁻¹ y
            xs = X[s.start:s.stop].T
            if len(s.below):
                _into(xs, dgemm(-1.0, X[s.below].T, s.rows_below, beta=1.0, c=xs, overwrite_c=1))
            _into(xs, dtrsm(1.0, s.diagonal, xs, side=1, lower=1, trans_a=0, diag=1, overwrite_b=1))
