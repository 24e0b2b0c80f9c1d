"""Receptance of the condensed modes of one harmonic at the contact coordinates, summed by series.

With no damping on harmonic ``h`` (the campaign's EPMC: structural damping enters the E-EBM only) the
modal impedances are ``z_r = ω_r² − s`` with one complex shift for all modes, ``s = (hω)² + i hωξ``
(:meth:`ringdamper.nonlinear.harmonic_balance.condensed.CondensedHBM._modal_impedance`), and the receptance the Jacobian
needs at every factorisation is

    G(s) = Ψ_C diag(1 / (ω_r² − s)) Ψ_Cᴴ        (p × p, over the m condensed modes: ≈ 8 p² m flops).

Most condensed modes of a Craig–Bampton model lie far above ``hω`` (the campaign's rings: 90 % of the
543 modes above 40 hω, the constraint modes of the stiff contact springs). For those *far* modes,
``ω_r² > FAR² |s₀|`` at the expansion point ``s₀`` (given when the receptance is built: a solve's start
point, :class:`ringdamper.nonlinear.harmonic_balance.condensed.CondensedHBM`), the geometric series

    1 / (ω_r² − s) = Σ_k s^k / ω_r^{2(k+1)},   |s| / ω_r² ≤ q = |s| / min_far ω_r²

turns their part of ``G`` into ``Σ_{k<K} s^k M_k`` with ``M_k = Ψ_F diag(ω_r^{−2(k+1)}) Ψ_Fᴴ`` formed once;
each term's remainder is below ``q^K / (1 − q)`` of it, and ``K`` is taken so that this is below
:data:`TOL` (rounding). The near modes keep the direct sum. An ``s`` for which the stored terms do not
reach :data:`TOL` gets the direct sum over all modes. On a campaign ring (a02_001: p = 210, m = 543;
FAR = 10: 17–41 near modes, q ≈ 0.01, K = 9) a harmonic's receptance takes 0.4–0.5 ms instead of 3.3 ms
and agrees with the direct sum to 4e-15 of its largest entry.

*Modal damping* (:class:`DampedReceptance`; the forced responses, whose harmonics carry the structural
damping ``c_r = 2 ζ_s ω_r``, with ``ξ = 0``). Then ``z_r = ω_r² − u² + i u c_r`` with ``u = hω``: one real
variable, but a damping coefficient per mode. With ``x = u / ω_r`` and ``β_r = c_r / ω_r``,

    1 / z_r = ω_r⁻² / (1 + iβ_r x − x²) = Σ_k P_k(β_r) u^k / ω_r^{k+2},
    P_0 = 1,  P_1 = −iβ,  P_k = −iβ P_{k−1} + P_{k−2},

the expansion of a rational function whose two poles lie on ``|x| = 1`` for ``β < 2`` (``x² − iβx − 1 = 0``),
so that ``|P_k| ≤ k + 1`` (``P_k`` is ``(−i)^k U_k(β/2)``, a Chebyshev polynomial of the second kind,
bounded by ``k + 1`` on ``[−1, 1]``). For the far modes (``ω_r > FAR·u₀`` at the expansion point ``u₀``,
and ``β_r ≤ 1``) the part of ``G`` is ``Σ_{k<K} u^k M_k``, ``M_k = Ψ_F diag(P_k(β_r) ω_r^{−(k+2)}) Ψ_Fᴴ``,
with ``K`` such that the remainder bound ``Σ_{k≥K} (k + 1) q^k`` stays below :data:`TOL`
(:func:`damped_terms_needed`, ``q = u / min_far ω_r``).
"""
from __future__ import annotations

import sys

import numpy as np

#: a mode is far when ω_r exceeds this multiple of |s₀|^½ (s₀: the expansion point)
FAR = 10.0
#: bound on the relative remainder of the series
TOL = 1e-17
#: the stored terms serve up to this multiple of |s₀|
REACH = 2.0


def terms_needed(q: float) -> int:
    """Terms ``K`` of the series that bring its remainder ``q^K / (1 − q)`` below :data:`TOL`;
    ``sys.maxsize`` where the series diverges (``q ≥ 1``: the direct sum serves)."""
    if q <= 0.0:
        return 1
    if q >= 1.0:
        return sys.maxsize
    return max(1, int(np.ceil(np.log(TOL * (1.0 - q)) / np.log(q))))


class Receptance:
    """``G(s)`` of the module docstring for the modes ``w2`` (ω_r², positive) with contact rows ``Psi``
    (p × m) and ``PsiH = Psiᴴ``; the far modes' terms are formed about ``s0`` when it is built, and
    nothing changes after that."""

    terms_needed = staticmethod(terms_needed)

    def __init__(self, w2: np.ndarray, Psi: np.ndarray, PsiH: np.ndarray, s0: complex):
        self.w2, self.Psi, self.PsiH = w2, Psi, PsiH
        self.terms: list = []
        self.near = self.far_min = None
        self._build(s0)

    def __call__(self, s: complex, exclude: np.ndarray | None = None) -> np.ndarray:
        """The receptance at the series variable ``s`` (``u`` for :class:`DampedReceptance`), without the
        modes ``exclude`` (near modes only: ``ValueError`` for a mode in the series)."""
        if exclude is not None and not np.all(np.isin(exclude, self.near)):
            raise ValueError("exclude: only modes summed directly can be left out of the receptance")
        K = self.terms_needed(abs(s) / self.far_min) if self.far_min else 0
        if K > len(self.terms):
            return self.direct(s, np.setdiff1d(np.arange(self.w2.size), exclude) if exclude is not None
                               else slice(None))
        G = self.direct(s, self.near if exclude is None else np.setdiff1d(self.near, exclude))
        if K:
            series = self.terms[K - 1].copy()                # Horner: M_0 + s (M_1 + s (M_2 + …))
            for k in range(K - 2, -1, -1):
                series *= s
                series += self.terms[k]
            G = G + series
        return G

    def direct(self, s: complex, modes) -> np.ndarray:
        """``Σ_r ψ_r ψ_rᴴ / (ω_r² − s)`` over ``modes`` (real arithmetic for real modes and ``s``)."""
        w = 1.0 / (self.w2[modes] - s)
        return (self.Psi[:, modes] * w) @ self.PsiH[modes]

    def _build(self, s0: complex) -> None:
        far = self.w2 > FAR ** 2 * abs(s0)
        self.near = np.flatnonzero(~far)
        self.terms = []
        if not far.any():
            return
        self.far_min = float(self.w2[far].min())
        inverse = 1.0 / self.w2[far]
        Psi, PsiH = self.Psi[:, far], self.PsiH[far]
        power = inverse.copy()
        for _ in range(terms_needed(REACH * abs(s0) / self.far_min)):
            self.terms.append((Psi * power) @ PsiH)
            power *= inverse


def damped_terms_needed(q: float) -> int:
    """Terms ``K`` of the damped series that bring its remainder bound ``Σ_{k≥K} (k + 1) q^k
    = q^K (K + 1 − K q) / (1 − q)²`` below :data:`TOL`; ``sys.maxsize`` where the series diverges
    (``q ≥ 1``: the direct sum serves)."""
    if q <= 0.0:
        return 1
    if q >= 1.0:
        return sys.maxsize
    K = 1
    while q ** K * (K + 1 - K * q) / (1.0 - q) ** 2 > TOL:
        K += 1
    return K


class DampedReceptance(Receptance):
    """``G(u) = Ψ diag(1 / (ω_r² − u² + i u c_r)) Ψᴴ`` for the modes ``w2`` (ω_r², positive) with viscous modal
    damping coefficients ``c`` and contact rows ``Psi`` (p × m), ``PsiH = Psiᴴ``: the far modes by the series
    of the module docstring (formed about ``u0`` when it is built), the others summed directly."""

    terms_needed = staticmethod(damped_terms_needed)

    def __init__(self, w2: np.ndarray, c: np.ndarray, Psi: np.ndarray, PsiH: np.ndarray, u0: float):
        self.c = np.asarray(c, float)
        super().__init__(w2, Psi, PsiH, u0)

    def direct(self, u: float, modes) -> np.ndarray:
        """``Σ_r ψ_r ψ_rᴴ / (ω_r² − u² + i u c_r)`` over ``modes``."""
        w = 1.0 / (self.w2[modes] - u * u + 1j * u * self.c[modes])
        return (self.Psi[:, modes] * w) @ self.PsiH[modes]

    def _build(self, u0: float) -> None:
        omega_r = np.sqrt(self.w2)
        beta = self.c / omega_r
        far = (omega_r > FAR * abs(u0)) & (np.abs(beta) <= 1.0)
        self.near = np.flatnonzero(~far)
        self.terms = []
        if not far.any():
            return
        self.far_min = float(omega_r[far].min())
        Psi, PsiH, inverse, ib = self.Psi[:, far], self.PsiH[far], 1.0 / omega_r[far], 1j * beta[far]
        previous, current = np.zeros_like(ib), np.ones_like(ib)           # P_{−1} = 0, P_0 = 1
        power = inverse * inverse                                           # ω_r^−(k+2)
        for _ in range(damped_terms_needed(REACH * abs(u0) / self.far_min)):
            self.terms.append((Psi * (current * power)) @ PsiH)
            previous, current = current, -ib * current + previous
            power = power * inverse
