"""SuperLU factors of a structurally symmetric sparse matrix under a symmetric fill-reducing ordering.

P A Pᵀ = L U with P from :mod:`ringdamper.fem.ordering`: SuperLU's own minimum degree on Aᵀ + A, or
a nested-dissection order applied to A before SuperLU factorises it in that order (``NATURAL``, up
to SuperLU's fill-neutral postorder of the elimination tree). ``SymmetricMode`` keeps the pivots on
the diagonal where threshold pivoting allows it; ``definite`` (A positive definite) takes every
pivot on the diagonal (no row interchanges: stable for a definite matrix, and L U = L D Lᵀ).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import splu

from .ordering import available, default_ordering, nested_dissection


class SymmetricLU:
    """``solve(b)`` = A⁻¹ b for a vector or an (n, k) block (SuperLU's solve); ``lu`` the SuperLU
    object of P A Pᵀ, ``perm`` the position in it of every row of A."""

    def __init__(self, A: sp.spmatrix, definite: bool = False, ordering: str | None = None):
        A = sp.csc_matrix(A)
        self.ordering = available(ordering or default_ordering(A.shape[0]))
        self.order = nested_dissection(A) if self.ordering == "nested_dissection" else None
        pivots = {"diag_pivot_thresh": 0.0} if definite else {}
        if self.order is None:
            self.lu = splu(A, permc_spec="MMD_AT_PLUS_A", options={"SymmetricMode": True}, **pivots)
        else:
            self.lu = splu(A[self.order][:, self.order].tocsc(), permc_spec="NATURAL",
                           options={"SymmetricMode": True}, **pivots)

    @property
    def shape(self) -> tuple[int, int]:
        return self.lu.shape

    @property
    def perm(self) -> np.ndarray:
        """Row i of A is row perm[i] of the factorised matrix (when no rows were interchanged)."""
        p = self.lu.perm_c
        return p if self.order is None else p[np.argsort(self.order)]

    def solve(self, b: np.ndarray) -> np.ndarray:
        if self.order is None:
            return self.lu.solve(b)
        x = self.lu.solve(np.asarray(b)[self.order])
        out = np.empty_like(x)
        out[self.order] = x
        return out
