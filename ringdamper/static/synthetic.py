"""Small test systems for the static contact solver: spring chains and two elastic blocks.

Conventions of ``ringdamper.static.solver``: G (3m × n) pair-major, d = u_ring − u_blisk in
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
    component: np.ndarray = None  # (n,) x/y/z component of each DoF (blocks only)
    points: np.ndarray = None  # (m, 2) x, y of each pair (blocks only)


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


def _block(nx, nz, z0, height, E, nu, quadratic):
    """Linear-elastic block [0,1]² × [z0, z0 + height] (hexahedral Q1 or Q2 mesh).

    Returns the basis, K, the node points (3, P) and the DoF of component c at point j, (3, P).
    """
    from skfem import Basis, BilinearForm, ElementHex1, ElementHex2, ElementVector, MeshHex, asm
    from skfem.models.elasticity import lame_parameters, linear_elasticity

    grid = np.linspace(0.0, 1.0, nx + 1)
    mesh = MeshHex.init_tensor(grid, grid, np.linspace(z0, z0 + height, nz + 1))
    element = ElementHex2() if quadratic else ElementHex1()
    basis = Basis(mesh, ElementVector(element), intorder=4 if quadratic else 3)
    K = asm(BilinearForm(linear_elasticity(*lame_parameters(E, nu))), basis)
    dofs = np.array(basis.split_indices())
    return basis, K, basis.doflocs[:, dofs[0]], dofs


def _lumped_body_force(basis, load):
    """Consistent nodal body force for a per-point force density load(x) -> (3, ...) array."""
    from skfem import LinearForm, asm

    @LinearForm
    def body(v, w):
        b = load(w.x)
        return b[0] * v[0] + b[1] * v[1] + b[2] * v[2]

    return asm(body, basis)


def two_blocks(nx=4, nz=2, E=100.0, nu=0.3, load=None, gap=None, clamp_ring_top=False,
               height=1.0, quadratic=False):
    """Block A (blisk, z ∈ [0,h], bottom clamped) under block B (ring, z ∈ [h,2h]).

    ``System.ring`` lists B's DoFs when B is held only by the contact (else None).
    Matching node pairs on z = h, local frame n = −z (B closes downwards), t1 = x, t2 = y.
    ``load(x)`` is the body force density on B (default: uniform −1 in z, resultant −h);
    ``gap(x, y)`` the initial gap (default 0). B is held only by the contact unless
    ``clamp_ring_top``.
    """
    basis_a, K_a, pts_a, dofs_a = _block(nx, nz, 0.0, height, E, nu, quadratic)
    basis_b, K_b, pts_b, dofs_b = _block(nx, nz, height, height, E, nu, quadratic)
    n_a = K_a.shape[0]
    dofs_b = dofs_b + n_a
    load = load or (lambda x: np.stack([0 * x[0], 0 * x[0], -1.0 + 0 * x[0]]))
    f = np.concatenate([np.zeros(n_a), _lumped_body_force(basis_b, load)])
    K = sp.block_diag([K_a, K_b]).tocsr()

    on_a = np.flatnonzero(np.isclose(pts_a[2], height))
    on_b = np.flatnonzero(np.isclose(pts_b[2], height))
    na, nb = on_a[np.lexsort(pts_a[:2, on_a])], on_b[np.lexsort(pts_b[:2, on_b])]
    assert np.allclose(pts_a[:2, na], pts_b[:2, nb])
    m = na.size
    frame = np.array([[0, 0, -1.0], [1.0, 0, 0], [0, 1.0, 0]])  # rows: n, t1, t2
    # row 3p + r of G: frame[r] · (u_B − u_A) at pair p
    rows = np.repeat(3 * np.arange(m)[:, None] + np.arange(3), 3, axis=1).ravel()
    comp = np.tile(np.arange(3), 3 * m)
    vals = np.tile(frame.ravel(), m)
    G = (sp.csr_matrix((vals, (rows, dofs_b[comp, np.repeat(nb, 9)])), shape=(3 * m, K.shape[0]))
         - sp.csr_matrix((vals, (rows, dofs_a[comp, np.repeat(na, 9)])), shape=(3 * m, K.shape[0])))
    G.eliminate_zeros()

    fixed = [dofs_a[:, np.isclose(pts_a[2], 0.0)].ravel()]
    if clamp_ring_top:
        fixed.append(dofs_b[:, np.isclose(pts_b[2], 2 * height)].ravel())
    free = np.setdiff1d(np.arange(K.shape[0]), np.concatenate(fixed))
    g0 = np.zeros(m) if gap is None else np.asarray(gap(*pts_a[:2, na]), float)
    component = np.empty(K.shape[0], int)
    for c in range(3):
        component[dofs_a[c]] = component[dofs_b[c]] = c
    return System(K[free][:, free].tocsr(), f[free], G[:, free].tocsr(), g0,
                  ring=None if clamp_ring_top else np.flatnonzero(free >= n_a),
                  component=component[free],
                  points=pts_a[:2, na].T)


def contact_forces(result):
    """λ stacked pair-major (N, T1, T2), the vector that enters Gᵀλ."""
    return np.column_stack([result.N0, result.tangential]).ravel()


def assert_kkt(result, system, kt, comp_tol=1e-12, balance_tol=1e-8):
    """Converged, N ≥ 0, gap ≥ 0, |N·g| small, equilibrium (with K itself) and, for a body held
    only by contact, its global force balance per direction: Σ_B (Gᵀλ) = Σ_B f."""
    assert result.status == 0, result.reason
    assert np.all(result.N0 >= 0) and np.all(result.gap >= 0)
    # exact complementarity is the contract (docs/static_contact.md), not a tolerance
    assert np.all(result.gap[result.in_contact] == 0.0) and np.all(result.N0[~result.in_contact] == 0.0)
    assert result.complementarity <= comp_tol
    lam = contact_forces(result)
    residual = system.K @ result.u + system.G.T @ lam - system.f
    assert np.linalg.norm(residual) <= balance_tol * np.linalg.norm(system.f)
    if system.ring is not None and system.component is not None:
        reaction = system.G.T @ lam
        for c in range(3):
            on = system.ring[system.component[system.ring] == c]
            applied = system.f[on].sum()
            scale = np.abs(system.f[system.ring]).sum()
            assert abs(reaction[on].sum() - applied) <= balance_tol * scale, (c, applied)
