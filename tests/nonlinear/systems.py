"""Small test structures for the nonlinear dynamics core (plain functions, no fixtures)."""
import numpy as np

from ringdamper.nonlinear.contact.friction import FrictionContacts
from ringdamper.nonlinear.harmonic_balance.structure import HarmonicData, Structure


def one_dof(H=1, m=2.0, k=100.0, kt=50.0, mu=0.3, N=10.0, kn=1e3, zero_tol=1e-9):
    """Mass m on spring k with one Jenkins element on its displacement (tangential t1)."""
    B = np.array([[0.0], [1.0], [0.0]])
    st = Structure.real(np.array([[m]]), np.array([[k]]), B, np.array([1.0]), np.array([1.0]),
                        H=H, zero_tol=zero_tol)
    return st, FrictionContacts(kn=kn, kt=kt, mu=mu, N0=N, gap=0.0)


def describing_function(a, m=2.0, k=100.0, kt=50.0, mu=0.3, N=10.0):
    """H = 1 describing-function dNNM of :func:`one_dof` at displacement amplitude ``a``:
    returns ω, ζ (docs/design.md §7 Jenkins oracle)."""
    a = np.asarray(a, float)
    a_s = mu * N / kt
    slip = a > a_s
    beta = np.arccos(np.clip(1 - 2 * a_s / a, -1, 1))
    kr = np.where(slip, kt / np.pi * (beta - 0.5 * np.sin(2 * beta)), kt)
    ki = np.where(slip, 4 * mu * N * (a - a_s) / (np.pi * a * a), 0.0)
    w = np.sqrt((k + kr) / m)
    return w, ki / (m * w) / (2 * w)


def two_dof(H=1, force_dof=0):
    """2-DoF chain (ground–k1–m1–k2–m2) with a friction contact between m2 and the ground
    (tangential t1 = x2, normal preloaded), forced and observed at ``force_dof``."""
    M = np.diag([1.0, 0.5])
    K = np.array([[3.0e4 + 1.0e4, -1.0e4], [-1.0e4, 1.0e4]])
    B = np.array([[0.0, 0.0], [0.0, 1.0], [0.0, 0.0]])
    e = np.eye(2)[force_dof]
    st = Structure.real(M, K, B, e, e, H=H)
    return st, FrictionContacts(kn=1e6, kt=1e3, mu=0.25, N0=20.0, gap=0.0)


def multi_dof(H=3, zero_tol=1e-9):
    """Three point masses A, B, C in the (x, y) plane (DoFs ``[xA, yA, xB, yB, xC, yC]``) with two
    3-D contact pairs to the ground: pair 0 on B, preloaded, normal = yB (its normal load varies
    with the motion); pair 1 on C with an initial gap, normal = yC (intermittent contact)."""
    M = np.diag([1.0, 1.0, 0.8, 0.8, 1.2, 1.2])
    K = np.zeros((6, 6))
    for (i, j), kk in zip([(0, 1), (1, 2), (0, 2)], [4e4, 2.5e4, 3e4]):   # mass–mass springs
        for dof in range(2):
            a, b = 2 * i + dof, 2 * j + dof
            K[np.ix_([a, b], [a, b])] += kk * np.array([[1, -1], [-1, 1]])
    K += np.diag([5e4, 1.5e5, 0.0, 0.0, 3e4, 9e4])            # ground springs
    K[0, 1] = K[1, 0] = 8e3                                  # in-plane coupling of A
    B = np.zeros((6, 6))
    B[0, 3], B[1, 2], B[2, 2], B[2, 3] = 1.0, 1.0, 0.4, 0.3  # pair 0: n = yB, t1 = xB, t2 mixed
    B[3, 5], B[4, 4], B[5, 5] = 1.0, 1.0, 0.5                # pair 1: n = yC, t1 = xC, t2 = .5 yC
    e = np.zeros(6)
    e[0] = 1.0
    st = Structure.real(M, K, B, e, e, H=H, zero_tol=zero_tol)
    contacts = FrictionContacts(kn=np.array([2e5, 2e5]), kt=np.array([1e5, 1e5]), mu=0.05,
                                N0=np.array([30.0, 0.0]), gap=np.array([0.0, 2e-4]))
    return st, contacts


def free_body(H=1, normal_coupling=0.0):
    """Mass m1 on a spring to the ground and a free mass m2 held only by friction on m1
    (t1 = x2 − x1). ``normal_coupling`` ε makes the normal gap follow ε·x1, so the friction limit
    varies in phase with the motion (a ratcheting, drifting case)."""
    M = np.diag([1.0, 0.3])
    K = np.array([[4e4, 0.0], [0.0, 0.0]])
    B = np.array([[normal_coupling, 0.0], [-1.0, 1.0], [0.0, 0.0]])
    e = np.array([1.0, 0.0])
    st = Structure.real(M, K, B, e, e, H=H)
    return st, FrictionContacts(kn=1e5, kt=3e4, mu=0.3, N0=50.0, gap=0.0)


def cyclic_sector(seed=3, ring_support=3e3, kb=2e4):
    """Sector of a toy bladed disk with a ring: DoFs ``[disk n, t1, t2, ring n, t1, t2, blade]``.
    Disk held to the ground, disk–disk and ring–ring springs to the next sector, ring radial hoop
    spring to the ground (and ``ring_support`` on its t1, t2; with 0 the ring's rotation and
    axial motion are free, held by friction only), blade (stiffness ``kb``) on the disk's axial
    DoF; one contact pair ring–disk. Returns ``(M0, M1, K0, K1, B)`` with the sector energy
    coupling ``x_jᵀ K1 x_{j+1}``."""
    rng = np.random.default_rng(seed)
    n = 7
    K0 = np.zeros((n, n))
    K1 = np.zeros((n, n))
    M0 = np.diag([1.0, 1.0, 1.0, 0.3, 0.3, 0.3, 0.5])
    M1 = np.zeros((n, n))
    kg = [3e4, 2e4, 2.5e4]                                    # disk to ground
    kd = [1e4, 1.5e4, 1.2e4]                                  # disk to next disk
    kr = [0.0, 6e3, 5e3]                                      # ring to next ring (n via hoop)
    for i in range(3):
        K0[i, i] += kg[i] + 2 * kd[i]
        K1[i, i] -= kd[i]
        K0[3 + i, 3 + i] += 2 * kr[i]
        K1[3 + i, 3 + i] -= kr[i]
    K0[3, 3] += 8e3                                          # ring hoop stiffness
    K0[4, 4] += ring_support                                 # optional elastic ring support
    K0[5, 5] += ring_support
    # blade on the disk axial DoF (stiffness kb)
    K0[np.ix_([2, 6], [2, 6])] += kb * np.array([[1, -1], [-1, 1]])
    A = 0.05 * rng.standard_normal((3, 3))
    K0[:3, :3] += 1e4 * (A + A.T)                             # some coupling inside the disk
    M1[2, 2] = 0.05                                           # consistent-mass-like coupling
    B = np.zeros((3, n))
    B[:, 3:6] = np.eye(3)
    B[:, 0:3] -= np.eye(3)
    return M0, M1, K0, K1, B


def cyclic_structure(n_sectors=6, engine_order=2, H=5, ring_support=3e3, kb=2e4):
    M0, M1, K0, K1, B = cyclic_sector(ring_support=ring_support, kb=kb)
    resp = np.zeros(7)
    resp[6] = 1.0

    def sector(h, sigma):
        e = np.exp(1j * sigma)
        K = K0 + K1 * e + K1.T * np.conj(e)
        M = M0 + M1 * e + M1.T * np.conj(e)
        if h == 0:
            K, M = K.real, M.real
        return HarmonicData(M=M, K=K, B=B.astype(complex) if h else B, response=resp,
                            force=resp.astype(complex) if h == 1 else None)

    st = Structure.cyclic(n_sectors, engine_order, H, sector)
    contacts = FrictionContacts(kn=1e5, kt=4e4, mu=0.3, N0=40.0, gap=0.0)
    return st, contacts, (M0, M1, K0, K1, B)


def assemble_full(n_sectors, M0, M1, K0, K1):
    """360° real matrices of the cyclic toy (sector j coupled to j ± 1)."""
    n = M0.shape[0]
    N = n_sectors
    M = np.zeros((N * n, N * n))
    K = np.zeros_like(M)
    for j in range(N):
        a, b = slice(j * n, (j + 1) * n), slice(((j + 1) % N) * n, ((j + 1) % N + 1) * n)
        M[a, a] += M0
        K[a, a] += K0
        M[a, b] += M1
        K[a, b] += K1
        M[b, a] += M1.T
        K[b, a] += K1.T
    return M, K
