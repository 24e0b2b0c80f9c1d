"""Local stability of harmonic-balance solutions by Hill's method (docs/method_limits.md §4).

A periodic solution ``q(t)`` is perturbed by ``δq = e^{λt} p(t)``, ``p`` periodic and expanded on
the same harmonics. In coordinates where the mass matrix is the identity (mass-normalised modes of
every harmonic) the linear part of harmonic ``h`` becomes
``ω_r² + (λ + ihω)² + (λ + ihω) c_r = z_h + λ(2ihω + c_r) + λ²``, so the Hill eigenproblem on the
real slots of the harmonic-balance unknowns is the quadratic pencil

    (λ² I + λ Δ₁ + J) v = 0,       Δ₁ = ⊕_h real(diag(c_r + 2ihω)),

with ``J`` the Jacobian of the real harmonic-balance residual (linear part plus the AFT Jacobian
of the contact forces) and ``real(·)`` the real form of a complex operator on ``(a; b)`` slots
(:func:`ringdamper.nonlinear.fourier.real_block`). It is solved in its companion form
``[[0, I], [−J, −Δ₁]]``. Every Floquet exponent appears in the Hill spectrum with copies shifted by
multiples of ``iω``; the truncation pollutes the copies far from the real axis, so the exponents
kept are those in the fundamental strip ``|Im λ| ≤ ω/2`` (Moore 2005, *Int. J. Numer. Meth. Eng.*
64:1431; Lazarus & Thomas 2010, *C. R. Mécanique* 338:510). The solution is stable when every kept
exponent has ``Re λ ≤ tol·ω`` (the tolerance absorbs the neutral exponents of undamped or free
rigid-body directions).

Forces that depend on velocity (:class:`ringdamper.nonlinear.contact.elements.TanhFriction`). The contact
force of the perturbation is ``δΛ = K_d(t) δd + K_v(t) δḋ`` with ``δḋ = e^{λt}(λ p_d + ṗ_d)``. The
AFT Jacobian ``K_c`` of the harmonic balance linearises along periodic perturbations, whose velocity
is ``ω ∂d/∂τ``: it holds ``K_d p_d + K_v ṗ_d``. The rest, ``λ K_v p_d``, is a damping: with the
velocity Jacobian ``K_v = F diag(∂f/∂ḋ) E`` on the contact slots (the AFT of the samples of
``∂f/∂ḋ(t)``, :attr:`ringdamper.nonlinear.contact.friction.ContactAFT.jac_velocity`, a real operator on
``(a; b)`` slots like ``K_c``) the pencil becomes

    (λ² I + λ (Δ₁ + Pᵀ K_v P) + J) v = 0,

``P`` the map from the modal slots to the contact slots, the one through which ``K_c`` enters ``J``.

Large models (a real ring keeps hundreds of modes per harmonic) are reduced first: the modes with
``ω_r > (H + band)·ω`` lie above every retained harmonic, their exponents far outside the strip,
so they are condensed onto the contact at ``λ = 0`` with their exact receptance ``1/z_r`` (a
residual flexibility ``G``, positive because ``ω_r > hω``, as in the condensed harmonic balance);
the contact stiffness the kept modes see is then ``K_eff = (I + K_c G)⁻¹ K_c``. (Condensing modes
*below* a harmonic as well would add negative flexibility and spurious real exponents.) A damping
that couples the modes (``C_off``, :mod:`ringdamper.nonlinear.harmonic_balance.structure`) keeps every mode of its
harmonic: ``Z_h`` and ``Δ₁`` take ``+ i h ω C_off`` and ``+ C_off``. With forces
that depend on velocity the force through the condensed modes, ``δΛ = (I + (K_c + λK_v) G)⁻¹
(K_c + λK_v) P η``, is rational in ``λ``; the pencil takes its expansion to first order at ``λ = 0``,
the point the condensed modes are taken at:

    Δ₁ + Pᵀ K_v,eff P,     K_v,eff = (I + K_c G)⁻¹ K_v (I + G K_c)⁻¹,

the velocity force of the contact displacement the condensed modes let through, ``(I + G K_c)⁻¹ P η``,
passed back through them. The terms left out are ``O(|λ| ‖G K_v‖)`` relative to it, the order of
the condensed modes' own ``λ`` terms left out (``O(|λ| hω/ω_r²)``); with no mode condensed
(``band = inf``) the pencil is exact.

Gauged rigid-body directions. Where the condensed HBM holds a free rigid-body direction of the ring
by its gauge (:mod:`ringdamper.nonlinear.harmonic_balance.condensed`: the mean position pinned, the unbalanced mean
force reported as drift), the solution is one of the held system, and so is its stability: those
directions are removed from the Hill problem. Otherwise their mean position, whose net contact
stiffness can be slightly negative there, contributes a small real exponent (≈ 0.02 1/s at
5.8e3 rad/s on the default ring) that states the drift already reported, not an instability of the
vibration. The held system has no mean motion along those directions, so they leave ``Δ₁`` as they
leave ``J`` (``Qᵀ J Q``, ``Qᵀ Δ₁ Q`` with ``Q`` a basis of the rest): with forces that depend on
velocity, the decay rate of the free body's mean velocity, which its damping by those forces gives it,
is not among the exponents either.

The linearisation of the hysteretic contact force by its AFT
Jacobian is the usual approximation of Hill's method for friction (Krack & Gross 2019, *Harmonic
Balance for Nonlinear Vibration Problems*, §5).
"""
from __future__ import annotations

import numpy as np
import scipy.linalg as sla
from scipy import sparse

from ringdamper.nonlinear.fourier import real_block
from ringdamper.nonlinear.harmonic_balance.condensed import apply_contact_jacobian

#: modes kept explicit in the Hill problem: ``ω_r ≤ (H + BAND)·ω`` (the others condensed)
BAND = 1.0


def hill_exponents(J: np.ndarray, D1: np.ndarray, omega: float) -> np.ndarray:
    """Floquet exponents of the pencil ``λ² I + λ D1 + J`` in the strip ``|Im λ| ≤ ω/2``."""
    N = J.shape[0]
    if J.shape != (N, N) or D1.shape != (N, N):
        raise ValueError(f"J and D1 must be square and alike, got {J.shape} and {D1.shape}")
    A = np.block([[np.zeros((N, N)), np.eye(N)], [-J, -D1]])
    lam = sla.eigvals(A, check_finite=False)
    return lam[np.abs(lam.imag) <= 0.5 * abs(omega) * (1 + 1e-9)]


def is_stable(exponents: np.ndarray, omega: float, tol: float = 1e-6) -> bool:
    """Every exponent has ``Re λ ≤ tol·ω``."""
    return bool(np.max(exponents.real, initial=-np.inf) <= tol * abs(omega))


def modal_hill_matrices(model, ev, omega: float, band: float = BAND):
    """``J`` and ``Δ₁`` of a forced condensed-HBM solution (:class:`~ringdamper.nonlinear.harmonic_balance.condensed.
    CondensedHBM`, evaluation ``ev`` with its full AFT Jacobian) on the modes kept explicit
    (``ω_r ≤ (H + band)·ω``), slots ``[η_0 | a_1, b_1 | … | a_H, b_H]`` (``η_h = a_h − i b_h``):
    ``J = ⊕_h real(diag(z_h)) + Pᵀ K_eff P`` and ``Δ₁ = ⊕_h real(diag(c_r + 2ihω)) + Pᵀ K_v,eff P``
    (the second term only for forces that depend on velocity) with ``P = ⊕_h real(Ψ_h)`` onto the
    contact slots and ``K_eff``, ``K_v,eff`` the contact's AFT and velocity Jacobians seen through the
    condensed modes, without the directions the gauge holds (module docstring)."""
    if ev.aft.jac is None or ev.aft.jac.shape[-1] != model.C:
        raise ValueError("the evaluation must carry the full contact Jacobian (jacobian=True)")
    if ev.aft.dlam_domega is not None and ev.aft.jac_velocity is None:
        raise ValueError("forces that depend on velocity must give their velocity Jacobian "
                         "(ContactAFT.jac_velocity)")
    Z, D1, Pfull, G, kept0 = _modal_blocks(model, omega, band)
    Kc = _contact_matrix(ev.aft.jac, model.p)
    condensed = any(np.any(g) for g in G)
    through = sla.lu_factor(_through_matrix(model, ev.aft.jac, G), overwrite_a=True,
                            check_finite=False) if condensed else None
    KP = Kc @ Pfull if through is None else sla.lu_solve(through, Kc @ Pfull, check_finite=False)
    J, D = Z + Pfull.T @ KP, D1
    if ev.aft.jac_velocity is not None:
        D = D + Pfull.T @ _velocity_force(_contact_matrix(ev.aft.jac_velocity, model.p), sla.block_diag(*G),
                                          Pfull, KP, through)
    if ev.gauge.shape[1]:                           # hold the gauged rigid-body directions
        Q = _held_space(model, ev.gauge, kept0, J.shape[0])
        J, D = Q.T @ J @ Q, Q.T @ D @ Q
    return J, D


def _modal_blocks(model, omega: float, band: float):
    """Linear parts of the Hill pencil on the modes kept explicit (``ω_r ≤ (H + band)·ω``, every
    mode of a harmonic whose damping couples them): ``⊕_h real(diag(z_h))``,
    ``⊕_h real(diag(c_r + 2ihω))`` (plus the coupling), the map ``P = ⊕_h real(Ψ_h)`` from their
    slots to the contact slots, the residual flexibility ``G = ⊕_h real(Ψ_h,c diag(1/z_c) Ψ_h,cᴴ)``
    of the condensed ones as its harmonics' diagonal blocks, and the indices of the modes of harmonic 0
    kept."""
    Z, D1, P, kept, G = [], [], [], [], []
    for h, m in enumerate(model.modal):
        z, _, _ = model._modal_impedance(h, omega, 0.0)
        c = model.damping[h]
        keep = np.sqrt(m.w2) <= (model.H + band) * omega
        coupling = model.coupling[h]
        if coupling is not None:                    # damping that couples the modes: keep them all
            keep[:] = True
        kept.append(np.flatnonzero(keep))
        rows = model._rows(h)
        receptance = _rest_receptance(model, h, omega, z, keep)
        if h == 0:
            Z.append(np.diag(z[keep].real))
            D1.append(np.diag(c[keep]) if coupling is None else np.diag(c) + coupling)
            P.append((rows, m.Psi[:, keep].real))
            G.append(receptance.real)
        else:
            Zh, Dh = np.diag(z[keep]), np.diag(c[keep] + 2j * h * omega)
            if coupling is not None:                # every mode kept: the coupling's full matrix
                Zh, Dh = model.explicit_impedance(h, omega, z), Dh + coupling
            Z.append(real_block(Zh))
            D1.append(real_block(Dh))
            P.append((rows, real_block(m.Psi[:, keep])))
            G.append(real_block(receptance))
    Pfull = np.zeros((model.n_d, sum(b.shape[1] for _, b in P)))
    col = 0
    for rows, b in P:
        Pfull[rows, col:col + b.shape[1]] = b
        col += b.shape[1]
    return sla.block_diag(*Z), sla.block_diag(*D1), Pfull, G, kept[0]


def _through_matrix(model, kc: np.ndarray, G: list) -> np.ndarray:
    """``I + K_c G`` (Fortran order, for an LU in place) with ``G = ⊕_h G_h`` block diagonal over the
    harmonics' contact slots: its columns of harmonic ``h`` are ``K_c[:, h] G_h``, formed pair by pair
    from the AFT Jacobian ``kc`` (np, 3, C, 3, C) as the transpose of ``G_hᵀ K_cᵀ[h, :]``
    (:func:`~ringdamper.nonlinear.harmonic_balance.condensed.apply_contact_jacobian`), so the zero blocks of ``G`` and
    of ``K_c`` cost nothing."""
    M = np.empty((model.n_d, model.n_d), order="F")
    kcT = kc.transpose(0, 3, 4, 1, 2)
    for h, Gh in enumerate(G):
        apply_contact_jacobian(Gh.T, kcT, model.fourier.slots(h), model.p, transposed=True,
                               out=M[:, model._rows(h)])
    M[np.arange(model.n_d), np.arange(model.n_d)] += 1.0
    return M


def _rest_receptance(model, h: int, omega: float, z: np.ndarray, keep: np.ndarray) -> np.ndarray:
    """``Σ_r ψ_r ψ_rᴴ / z_r`` over the modes of harmonic ``h`` not kept (``~keep``): the model's receptance of
    its condensed modes (:meth:`~ringdamper.nonlinear.harmonic_balance.condensed.CondensedHBM.receptance`, summed by its
    series where it has one), less the condensed modes kept and plus the explicit modes not kept, both
    few."""
    m, condensed, explicit = model.modal[h], model.Cset[h], model.S[h]
    G = model.receptance(h, omega, 0.0, z)
    for modes, sign in ((condensed[keep[condensed]], -1.0), (explicit[~keep[explicit]], 1.0)):
        if modes.size:
            G = G + sign * ((m.Psi[:, modes] / z[modes]) @ m.Psi[:, modes].conj().T)
    return G


def _velocity_force(Kv, G: np.ndarray, P: np.ndarray, KP: np.ndarray, through) -> np.ndarray:
    """``K_v,eff P = (I + K_c G)⁻¹ K_v (I + G K_c)⁻¹ P``: the contact force per unit ``λ`` of the
    velocity Jacobian ``K_v``, to first order in ``λ`` through the modes condensed at ``λ = 0``
    (module docstring), with ``through`` the LU of ``I + K_c G`` (None when no mode is condensed:
    ``K_v P``) and ``KP = (I + K_c G)⁻¹ K_c P``, whence ``(I + G K_c)⁻¹ P = P − G KP`` (push-through
    identity: no second factorisation)."""
    if through is None:
        return Kv @ P
    return sla.lu_solve(through, Kv @ (P - G @ KP), check_finite=False)


def _held_space(model, gauge: np.ndarray, kept0: np.ndarray, n: int) -> np.ndarray:
    """Orthonormal basis of the ``n`` explicit modal slots orthogonal to the gauged rigid-body
    directions ``gauge`` (columns in the zero-mode space of harmonic 0, whose kept modes ``kept0``
    have the first slots)."""
    E = np.zeros((n, gauge.shape[1]))
    E[np.searchsorted(kept0, model.S[0][model.zero_modes])] = gauge
    return sla.null_space(E.T)


def _contact_matrix(jac: np.ndarray, p: int) -> sparse.csr_array:
    """AFT Jacobian on the slot-major contact layout (sparse: one 3C × 3C block per pair):
    ``jac[q, i, c, j, c']`` at ``(c·p + 3q + i, c'·p + 3q + j)``."""
    npairs, _, C = jac.shape[:3]
    q, i, c, j, c2 = np.indices(jac.shape).reshape(5, -1)
    keep = jac.ravel() != 0
    rows, cols = c * p + 3 * q + i, c2 * p + 3 * q + j
    return sparse.csr_array((jac.ravel()[keep], (rows[keep], cols[keep])), shape=(C * p, C * p))
