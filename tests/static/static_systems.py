"""Small test systems for the static contact solver: spring chains and two elastic blocks.

Conventions of ``ringdamper.contact.static``: G (3m × n) pair-major, d = u_ring − u_blisk in
the local frame (n, t1, t2), d_n > 0 closing.
"""
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp


@dataclass
class System:
    """K u + Gᵀλ = f with m pairs; ``ring`` marks the DoFs of the body held only by contact."""

    K: sp.csr_matrix
    f: np.ndarray
    G: sp.csr_matrix
    g0: np.ndarray
    ring: np.ndarray = None
    normals: np.ndarray = None  # (m, 3) global normal of each pair (blocks only)


def chain_stiffness(k):
    """Stiffness of springs k[0..e-1] in series, node 0 clamped: (e × e), DoF i = node i + 1."""
    k = np.asarray(k, float)
    main = k + np.append(k[1:], 0.0)
    return sp.diags([main, -k[1:], -k[1:]], [0, 1, -1], format="csr")


def chain_flexibilities(k):
    """Tip displacement per unit force at node i+1 (= Σ_{j≤i} 1/k_j) and the tip flexibility."""
    c = np.cumsum(1.0 / np.asarray(k, float))
    return c, c[-1]


def wall_chain(k, loads, g0):
    """Clamped chain whose tip faces a rigid wall at distance g0 (one pair; t-rows are empty)."""
    n = len(k)
    G = sp.csr_matrix(([1.0], ([0], [n - 1])), shape=(3, n))
    return System(chain_stiffness(k), np.asarray(loads, float), G, np.array([float(g0)]))


def floating_pair(k_a, k_b, push, g0):
    """Clamped chain A (tip at the right) and a free 2-node body B (spring k_b) pushed left.

    B is held only by the contact: K is singular. DoFs: A's nodes, then B's near and far node.
    """
    n_a = len(k_a)
    K = sp.block_diag([chain_stiffness(k_a), k_b * sp.csr_matrix([[1.0, -1.0], [-1.0, 1.0]])])
    f = np.zeros(n_a + 2)
    f[-1] = -push
    # normal −x (B closes by moving left): d_n = −(u_B,near − u_A,tip)
    G = sp.csr_matrix(([1.0, -1.0], ([0, 0], [n_a - 1, n_a])), shape=(3, n_a + 2))
    return System(K.tocsr(), f, G, np.array([float(g0)]), ring=np.array([n_a, n_a + 1]))


def _block(nx, nz, z0, height, E, nu):
    """Linear-elastic unit-square block [0,1]² × [z0, z0 + height], hexahedral Q1 mesh."""
    from skfem import Basis, BilinearForm, ElementHex1, ElementVector, MeshHex, asm
    from skfem.models.elasticity import lame_parameters, linear_elasticity

    grid = np.linspace(0.0, 1.0, nx + 1)
    mesh = MeshHex.init_tensor(grid, grid, np.linspace(z0, z0 + height, nz + 1))
    basis = Basis(mesh, ElementVector(ElementHex1()), intorder=3)
    K = asm(BilinearForm(linear_elasticity(*lame_parameters(E, nu))), basis)
    return mesh, basis, K


def _lumped_body_force(basis, load):
    """Consistent nodal body force for a per-point force density load(x) -> (3, ...) array."""
    from skfem import LinearForm, asm

    @LinearForm
    def body(v, w):
        b = load(w.x)
        return b[0] * v[0] + b[1] * v[1] + b[2] * v[2]

    return asm(body, basis)


def two_blocks(nx=4, nz=2, E=100.0, nu=0.3, load=None, gap=None, clamp_ring_top=False):
    """Block A (blisk, z ∈ [0,1], bottom clamped) under block B (ring, z ∈ [1,2]).

    Matching node pairs on z = 1, local frame n = −z (B closes downwards), t1 = x, t2 = y.
    ``load(x)`` is the body force density on B (default: uniform −1 in z); ``gap(x, y)`` the
    initial gap (default 0). B is held only by the contact unless ``clamp_ring_top``.
    """
    mesh_a, basis_a, K_a = _block(nx, nz, 0.0, 1.0, E, nu)
    mesh_b, basis_b, K_b = _block(nx, nz, 1.0, 1.0, E, nu)
    n_a = K_a.shape[0]
    load = load or (lambda x: np.stack([0 * x[0], 0 * x[0], -1.0 + 0 * x[0]]))
    f = np.concatenate([np.zeros(n_a), _lumped_body_force(basis_b, load)])
    K = sp.block_diag([K_a, K_b]).tocsr()

    top_a = np.flatnonzero(np.isclose(mesh_a.p[2], 1.0))
    bottom_b = np.flatnonzero(np.isclose(mesh_b.p[2], 1.0))
    order_a = np.lexsort(mesh_a.p[:2, top_a])
    order_b = np.lexsort(mesh_b.p[:2, bottom_b])
    na, nb = top_a[order_a], bottom_b[order_b]
    assert np.allclose(mesh_a.p[:2, na], mesh_b.p[:2, nb])
    m = na.size
    frame = np.array([[0, 0, -1.0], [1.0, 0, 0], [0, 1.0, 0]])  # rows: n, t1, t2
    rows, cols, vals = [], [], []
    for p in range(m):
        for r in range(3):
            for c in range(3):
                if frame[r, c]:
                    rows += [3 * p + r, 3 * p + r]
                    cols += [n_a + basis_b.nodal_dofs[c, nb[p]], basis_a.nodal_dofs[c, na[p]]]
                    vals += [frame[r, c], -frame[r, c]]
    G = sp.csr_matrix((vals, (rows, cols)), shape=(3 * m, K.shape[0]))

    fixed = list(basis_a.nodal_dofs[:, np.isclose(mesh_a.p[2], 0.0)].ravel())
    if clamp_ring_top:
        fixed += list(n_a + basis_b.nodal_dofs[:, np.isclose(mesh_b.p[2], 2.0)].ravel())
    free = np.setdiff1d(np.arange(K.shape[0]), fixed)
    xy = mesh_a.p[:2, na]
    g0 = np.zeros(m) if gap is None else np.asarray(gap(*xy), float)
    ring = np.flatnonzero(free >= n_a)
    return System(K[free][:, free].tocsr(), f[free], G[:, free].tocsr(), g0, ring=ring,
                  normals=np.tile(frame[0], (m, 1)))
