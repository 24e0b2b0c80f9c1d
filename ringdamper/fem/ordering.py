"""Fill-reducing symmetric orderings for the sparse factorisations of :mod:`ringdamper.fem.linalg`.

Two orderings of a structurally symmetric matrix A, applied as P A Pᵀ:

* ``"minimum_degree"``: SuperLU's multiple minimum degree on the structure of Aᵀ + A
  (``permc_spec="MMD_AT_PLUS_A"``), computed inside the factorisation; always available;
* ``"nested_dissection"``: METIS's multilevel nested dissection (George 1973; Karypis & Kumar 1998,
  ``METIS_NodeND``) of the graph of A (one vertex per row, an edge per off-diagonal entry), through
  the ``pymetis`` wheel. METIS compresses rows of identical structure (the three DoFs of a node)
  before it orders.

The default, :func:`default_ordering`, is chosen by measurement on the sector's matrices
(docs/investigations/2026-12-01-sparse-solver.md): minimum degree up to :data:`NESTED_DISSECTION_ROWS`
rows (the 1x and 2x meshes: equal fill within 16 %, either way), nested dissection above it (the 3x
mesh's blisk interior, 116 190 rows: 31 % less fill, half the factorisation time). Where ``pymetis``
is not installed nested dissection falls back to minimum degree (:func:`available`).
"""

from __future__ import annotations

import importlib.util

import numpy as np
import scipy.sparse as sp

ORDERINGS = ("minimum_degree", "nested_dissection")
#: matrices with more rows than this are ordered by nested dissection by default
NESTED_DISSECTION_ROWS = 50_000


def default_ordering(n_rows: int) -> str:
    """The measured default for a matrix of ``n_rows`` rows (before the fallback of :func:`available`)."""
    return "nested_dissection" if n_rows > NESTED_DISSECTION_ROWS else "minimum_degree"


def available(ordering: str) -> str:
    """``ordering`` if it can run here, else ``"minimum_degree"`` (nested dissection without
    ``pymetis``); an unknown name is an error naming the allowed ones."""
    if ordering not in ORDERINGS:
        raise ValueError(f"ordering {ordering!r} is not one of {ORDERINGS}")
    if ordering == "nested_dissection" and importlib.util.find_spec("pymetis") is None:
        return "minimum_degree"
    return ordering


def nested_dissection(A: sp.spmatrix) -> np.ndarray:
    """METIS's nested-dissection order of the rows of A: row ``order[k]`` of A is row k of P A Pᵀ."""
    import pymetis

    A = sp.csr_matrix(A)
    G = sp.csr_matrix((np.ones(A.nnz), A.indices, A.indptr), shape=A.shape)
    G = (G + G.T).tocsr()
    G.setdiag(0)
    G.eliminate_zeros()
    perm, _ = pymetis.nested_dissection(pymetis.CSRAdjacency(G.indptr, G.indices))
    return np.asarray(perm, dtype=np.int64)
