"""Vectorised element kernels of 3-D elasticity on a scalar scikit-fem basis.

The vector DoFs of scalar node a are (3a, 3a+1, 3a+2). All element matrices are built at once with
einsum over (element, quadrature point) instead of per pair of basis functions: for the 27-node
brick this is ~50x faster than a generic bilinear form.

St. Venant–Kirchhoff, total Lagrangian (e.g. Bonet & Wood, *Nonlinear Continuum Mechanics*, ch. 6):
F = I + grad u, E = (F^T F - I)/2, S = lambda tr(E) I + 2 mu E, f_int = integral (F S) : grad v.
Consistent tangent for the variation delta = N_b e_d, tested by N_a e_c (p = grad N, Q_ac = (F p_a)_c):

    K_ac,bd = integral  lambda Q_ac Q_bd + mu (F F^T)_cd (p_a . p_b) + mu Q_bc Q_ad     (material)
                      + delta_cd  p_a^T S p_b                                          (geometric)

At u = 0 the material part is the linear elastic stiffness and the geometric part vanishes.

The prestressed vibration stiffness of ``fem.prestress`` is the linear one, K + K_sigma: the
geometric term above with S replaced by the small-strain stress sigma = C eps(u) of a linear static
solution (:func:`stress_stiffness`), e.g. Cook et al., *Concepts and Applications of FEA*, ch. 18.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from skfem import Basis


def lame(young: float, poisson: float) -> tuple[float, float]:
    """(lambda, mu) of an isotropic material."""
    return (young * poisson / ((1 + poisson) * (1 - 2 * poisson)), young / (2 * (1 + poisson)))


#: Elements per assembly chunk. Every element quantity (gradients at the quadrature points, element
#: matrices: 52 kB per 27-node brick) is formed one chunk at a time and summed into the global matrix,
#: so no stack over the whole mesh is held (a 3x mesh has 4806 elements).
CHUNK_ELEMENTS = 256


def element_chunks(basis: Basis, size: int | None = None) -> list[np.ndarray]:
    """Positions 0..n_elements-1 of the basis's elements in consecutive chunks of at most ``size``
    (default :data:`CHUNK_ELEMENTS`)."""
    n, size = basis.nelems, size or CHUNK_ELEMENTS
    return [np.arange(start, min(start + size, n)) for start in range(0, n, size)]


def _gradients(basis: Basis, chunk: np.ndarray) -> np.ndarray:
    """grad N_a at every quadrature point of the chunk's elements: (element, qp, a, direction)."""
    return np.stack([phi[0].grad[:, chunk] for phi in basis.basis], axis=0).transpose(2, 3, 0, 1)


def _values(basis: Basis, chunk: np.ndarray) -> np.ndarray:
    """N_a at every quadrature point of the chunk's elements: (element, qp, a)."""
    return np.stack([np.asarray(phi[0])[chunk] for phi in basis.basis], axis=0).transpose(1, 2, 0)


def _element_dofs(basis: Basis, chunk: np.ndarray) -> np.ndarray:
    """(element, 3 * n_local) global vector DoFs in local order (a, c) -> 3a + c."""
    nodes = basis.element_dofs[:, chunk].T
    return (3 * nodes[:, :, None] + np.arange(3)).reshape(len(nodes), -1)


def _assemble_matrix(basis: Basis, element_matrices) -> sp.csr_matrix:
    """Sum the element matrices ``element_matrices(chunk)`` -> (element, a, c, b, d) of every chunk
    into a global CSR matrix (the chunk's COO indices 32-bit, as SciPy's conversion stores them)."""
    n = 3 * basis.N
    out = sp.csr_matrix((n, n))
    for chunk in element_chunks(basis):
        ke = element_matrices(chunk)
        m = ke.shape[1] * ke.shape[2]
        dofs = _element_dofs(basis, chunk).astype(np.int32)
        rows = np.repeat(dofs, m, axis=1).ravel()
        cols = np.tile(dofs, (1, m)).ravel()
        out += sp.coo_matrix((ke.ravel(), (rows, cols)), shape=(n, n)).tocsr()
    return out


def _assemble_vector(basis: Basis, element_vectors) -> np.ndarray:
    """Sum the element vectors ``element_vectors(chunk)`` -> (element, a, c) of every chunk."""
    out = np.zeros(3 * basis.N)
    for chunk in element_chunks(basis):
        np.add.at(out, _element_dofs(basis, chunk).ravel(), element_vectors(chunk).ravel())
    return out


def _displacement_gradient(basis: Basis, chunk: np.ndarray, grads: np.ndarray, u: np.ndarray) -> np.ndarray:
    ue = u[_element_dofs(basis, chunk)].reshape(grads.shape[0], -1, 3)  # (e, a, c)
    return np.einsum("eac,eqai->eqci", ue, grads)


def _deformation(basis, chunk, grads, u, lam, mu):
    """F and S at the chunk's quadrature points."""
    eye = np.eye(3)
    F = eye + (0.0 if u is None else _displacement_gradient(basis, chunk, grads, u))
    F = np.broadcast_to(F, grads.shape[:2] + (3, 3))
    E = 0.5 * (np.einsum("eqki,eqkj->eqij", F, F) - eye)
    S = lam * np.trace(E, axis1=2, axis2=3)[..., None, None] * eye + 2 * mu * E
    return F, S


def tangent_stiffness(basis: Basis, young: float, poisson: float, u=None) -> sp.csr_matrix:
    """Consistent SVK tangent at displacement u (None: the linear elastic stiffness)."""
    lam, mu = lame(young, poisson)

    def element_matrices(chunk):
        grads, wj = _gradients(basis, chunk), basis.dx[chunk]
        F, S = _deformation(basis, chunk, grads, u, lam, mu)
        Q = np.einsum("eqck,eqak->eqac", F, grads)
        FF = np.einsum("eqck,eqdk->eqcd", F, F)
        PP = np.einsum("eqak,eqbk->eqab", grads, grads)
        ke = (lam * np.einsum("eq,eqac,eqbd->eacbd", wj, Q, Q, optimize=True)
              + mu * np.einsum("eq,eqcd,eqab->eacbd", wj, FF, PP, optimize=True)
              + mu * np.einsum("eq,eqbc,eqad->eacbd", wj, Q, Q, optimize=True))
        if u is not None:
            ke += _geometric(grads, wj, S)
        return ke

    return _assemble_matrix(basis, element_matrices)


def _geometric(grads: np.ndarray, wj: np.ndarray, stress: np.ndarray) -> np.ndarray:
    """Element geometric stiffness delta_cd integral p_a^T sigma p_b: (element, a, c, b, d)."""
    geo = np.einsum("eq,eqak,eqkl,eqbl->eab", wj, grads, stress, grads, optimize=True)
    return geo[:, :, None, :, None] * np.eye(3)[None, None, :, None, :]


def _small_strain_stress(basis, chunk, grads, lam, mu, u):
    G = _displacement_gradient(basis, chunk, grads, u)
    eps = 0.5 * (G + np.swapaxes(G, -1, -2))
    return lam * np.trace(eps, axis1=2, axis2=3)[..., None, None] * np.eye(3) + 2 * mu * eps


def small_strain_stress(basis: Basis, young: float, poisson: float, u: np.ndarray) -> np.ndarray:
    """sigma = lambda tr(eps) I + 2 mu eps, eps = (grad u + grad u^T)/2, at the quadrature points:
    (element, qp, 3, 3)."""
    lam, mu = lame(young, poisson)
    return np.concatenate([_small_strain_stress(basis, c, _gradients(basis, c), lam, mu, u)
                           for c in element_chunks(basis)])


def stress_stiffness(basis: Basis, young: float, poisson: float, u: np.ndarray) -> sp.csr_matrix:
    """K_sigma of the small-strain stress of ``u``: v^T K_sigma w = integral sigma : (grad v^T grad w),
    linear in u (the geometric stiffness of a linear prestress)."""
    lam, mu = lame(young, poisson)

    def element_matrices(chunk):
        grads = _gradients(basis, chunk)
        return _geometric(grads, basis.dx[chunk], _small_strain_stress(basis, chunk, grads, lam, mu, u))

    return _assemble_matrix(basis, element_matrices)


def internal_force(basis: Basis, young: float, poisson: float, u: np.ndarray) -> np.ndarray:
    """SVK internal force f_int(u) = integral (F S) : grad v."""
    lam, mu = lame(young, poisson)

    def element_vectors(chunk):
        grads, wj = _gradients(basis, chunk), basis.dx[chunk]
        F, S = _deformation(basis, chunk, grads, u, lam, mu)
        P = np.einsum("eqck,eqkj->eqcj", F, S)
        return np.einsum("eq,eqaj,eqcj->eac", wj, grads, P, optimize=True)

    return _assemble_vector(basis, element_vectors)


def mass_matrix(basis: Basis, density: float, components=(0, 1, 2)) -> sp.csr_matrix:
    """rho integral u . v over the given components; components (0, 1) is the spin-softening M_r."""
    sel = np.zeros((3, 3))
    sel[list(components), list(components)] = 1.0

    def element_matrices(chunk):
        vals = _values(basis, chunk)
        scalar = density * np.einsum("eq,eqa,eqb->eab", basis.dx[chunk], vals, vals, optimize=True)
        return scalar[:, :, None, :, None] * sel[None, None, :, None, :]

    return _assemble_matrix(basis, element_matrices)


def centrifugal_load(basis: Basis, density: float, omega: float) -> np.ndarray:
    """f = rho Omega^2 integral (x, y, 0) . v: the centrifugal body force about Z."""
    x = np.moveaxis(np.array(basis.global_coordinates()), 0, -1)  # (e, q, 3)
    x[..., 2] = 0.0

    def element_vectors(chunk):
        return density * omega**2 * np.einsum("eq,eqa,eqc->eac", basis.dx[chunk], _values(basis, chunk), x[chunk])

    return _assemble_vector(basis, element_vectors)
