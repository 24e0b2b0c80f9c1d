"""Linear prestress K + K_sigma(sigma = C eps(u)): exact on affine fields, and the centrifugal
stiffening of a rotating cantilever matches Southwell's coefficient."""
import numpy as np
import pytest
import scipy.linalg as sla
from skfem import Basis, ElementHex2, MeshHex

from ringdamper.fem.elasticity import (
    centrifugal_load,
    mass_matrix,
    small_strain_stress,
    stress_stiffness,
    tangent_stiffness,
)

E, NU, RHO = 2.0e11, 0.3, 7800.0


def box_basis(lx, ly, lz, nx):
    mesh = MeshHex.init_tensor(np.linspace(0, lx, nx + 1), np.linspace(-ly / 2, ly / 2, 2),
                               np.linspace(-lz / 2, lz / 2, 2))
    return Basis(mesh, ElementHex2(), intorder=4)


def affine(basis, A):
    """Vector DoFs of the field x -> A x (exact in the quadratic space)."""
    return (basis.doflocs.T @ A.T).ravel()


def test_stress_stiffness_is_exact_on_affine_fields():
    basis = box_basis(0.3, 0.1, 0.05, 3)
    rng = np.random.default_rng(3)
    U, A, B = (rng.standard_normal((3, 3)) * 1e-3 for _ in range(3))
    eps = 0.5 * (U + U.T)
    lam, mu = E * NU / ((1 + NU) * (1 - 2 * NU)), E / (2 * (1 + NU))
    sigma = lam * np.trace(eps) * np.eye(3) + 2 * mu * eps
    u = affine(basis, U)
    assert np.allclose(small_strain_stress(basis, E, NU, u), sigma, rtol=1e-10, atol=1e-6 * abs(sigma).max())
    Ks = stress_stiffness(basis, E, NU, u)
    volume = 0.3 * 0.1 * 0.05
    expected = volume * np.einsum("ck,kl,cl->", A, sigma, B)     # integral sum_c (grad v)_ck sigma_kl (grad w)_cl
    assert affine(basis, A) @ Ks @ affine(basis, B) == pytest.approx(expected, rel=1e-10)
    assert abs(Ks - Ks.T).max() <= 1e-12 * abs(Ks).max()
    # linear in u: the stress of a linear state
    Ks2 = stress_stiffness(basis, E, NU, 2 * u)
    assert abs(Ks2 - 2 * Ks).max() <= 1e-12 * abs(Ks).max()


def euler_bernoulli_rotating(L, EI, rhoA, Omega, n=120):
    """First bending omega^2 of a rotating cantilever (hub radius 0) from the 1-D Euler-Bernoulli
    equation (EI w'')'' - (T w')' = rhoA omega^2 w, T(x) = rhoA Omega^2 (L^2 - x^2)/2, with Hermite
    cubic elements: the independent oracle."""
    le, g = L / n, np.polynomial.legendre.leggauss(6)
    size = 2 * (n + 1)
    Kb, Kg, M = (np.zeros((size, size)) for _ in range(3))
    for e in range(n):
        for xi, w in zip(*g):
            s = (xi + 1) / 2
            x, wj = (e + s) * le, w * le / 2
            N = np.array([1 - 3 * s**2 + 2 * s**3, le * (s - 2 * s**2 + s**3), 3 * s**2 - 2 * s**3, le * (s**3 - s**2)])
            dN = np.array([6 * s**2 - 6 * s, le * (1 - 4 * s + 3 * s**2),
                           6 * s - 6 * s**2, le * (3 * s**2 - 2 * s)]) / le
            d2N = np.array([12 * s - 6, le * (6 * s - 4), 6 - 12 * s, le * (6 * s - 2)]) / le**2
            i = slice(2 * e, 2 * e + 4)
            Kb[i, i] += wj * EI * np.outer(d2N, d2N)
            Kg[i, i] += wj * rhoA * Omega**2 * (L**2 - x**2) / 2 * np.outer(dN, dN)
            M[i, i] += wj * rhoA * np.outer(N, N)
    f = slice(2, None)
    return sla.eigh((Kb + Kg)[f, f], M[f, f], eigvals_only=True)[0]


def test_rotating_cantilever_matches_euler_bernoulli():
    """Uniform cantilever clamped on the spin axis, spinning about Z at Omega = omega_0, first bending
    mode out of the plane of rotation (no spin softening acts on it): omega^2 - omega_0^2 against the
    1-D Euler-Bernoulli beam under its centrifugal tension (:func:`euler_bernoulli_rotating`; about
    1.18 Omega^2, cf. Southwell's coefficient 1.19). Slender (L/h = 50, width 2h so that the flapwise
    mode is the first), nu = 0 so that the 3-D bar is a beam; tolerance 0.5 % on the rise."""
    L, h = 1.0, 0.02
    basis = box_basis(L, 2 * h, h, 24)
    n = 3 * basis.N
    K = tangent_stiffness(basis, E, 0.0)
    M = mass_matrix(basis, RHO)
    Mr = mass_matrix(basis, RHO, components=(0, 1))
    free = np.setdiff1d(np.arange(n), (3 * np.flatnonzero(basis.doflocs[0] < 1e-12)[:, None]
                                       + np.arange(3)).ravel())
    sub = np.ix_(free, free)

    def first(Kmat):
        w2, vec = sla.eigh(Kmat[sub].toarray(), M[sub].toarray(), subset_by_index=(0, 0))
        assert np.linalg.norm(vec[2::3, 0]) > 0.99 * np.linalg.norm(vec[:, 0])   # flapwise (Z)
        return w2[0]

    EI, rhoA = E * 2 * h * h**3 / 12, RHO * 2 * h * h
    w0 = first(K)
    assert w0 == pytest.approx(euler_bernoulli_rotating(L, EI, rhoA, 0.0), rel=1e-2)
    Omega = np.sqrt(w0)
    u = np.zeros(n)
    u[free] = sla.solve((K - Omega**2 * Mr)[sub].toarray(), centrifugal_load(basis, RHO, Omega)[free],
                        assume_a="sym")
    rise = first(K + stress_stiffness(basis, E, 0.0, u) - Omega**2 * Mr) - w0
    oracle = euler_bernoulli_rotating(L, EI, rhoA, Omega) - euler_bernoulli_rotating(L, EI, rhoA, 0.0)
    assert rise == pytest.approx(oracle, rel=5e-3)
    assert 1.15 < rise / Omega**2 < 1.20
