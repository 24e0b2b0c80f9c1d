"""Forced-response harmonic balance (paper Eq. 1; docs/design.md §3.5):

    M q̈ + C q̇ + K q + Bᵀ λ(Bq) = Re(γ F̂_h e^{ihωt}),

with structural modal damping ``C`` (ratio ζ_s, or the structure's ``C``), condensed as in
:mod:`ringdamper.nonlinear.condensed` (ξ = 0). Unknowns ``z = [y, ω]``.

The Jacobian is returned as an operator (:class:`ringdamper.nonlinear.condensed.CoreJacobian`
bordered by the ω column, :mod:`ringdamper.nonlinear.jacobian`), as the EPMC's: Newton forms it
when it factorises, and the continuation's tangents are solved by GMRES on the corrector's last LU
(:class:`ringdamper.nonlinear.krylov.LaggedSolver`) instead of a factorisation each.
"""
from __future__ import annotations

import numpy as np

from ringdamper.nonlinear.condensed import CondensedHBM
from ringdamper.nonlinear.jacobian import bordered


class ForcedProblem:
    """Residual of ``z = [y, ω]`` (one equation fewer than unknowns: the continuation closes it)."""

    def __init__(self, model: CondensedHBM):
        if not model.forced:
            raise ValueError("the condensed model must be built with forced=True")
        self.model = model

    def fun(self, z: np.ndarray, jacobian: bool = True):
        ev = self.model.evaluate(z[:-1], z[-1], 0.0, jacobian)
        J = bordered(ev.J, ev.dr_domega) if jacobian else None
        return ev.r, J, ev.trivial, self.model.n_core, ev

    def at_frequency(self, omega: float):
        """Residual of ``y`` alone at fixed ω (square)."""
        def fun(y, jacobian=True):
            ev = self.model.evaluate(y, omega, 0.0, jacobian)
            return ev.r, ev.J, ev.trivial, self.model.n_core, ev
        return fun

    def scale(self, z: np.ndarray) -> np.ndarray:
        return np.concatenate((self.model.core_scale(z[:-1]), (abs(z[-1]),)))

    def linear_guess(self, omega: float, stiffness: np.ndarray) -> np.ndarray:
        """Response of the linearised stuck system (contact springs ``stiffness`` (p,)) at ω,
        solved exactly in the modes of every harmonic."""
        m = self.model
        d = np.zeros((m.C, m.p))
        etas = []
        for h, mh in enumerate(m.modal):
            z, _, _ = m._modal_impedance(h, omega, 0.0)
            Z = np.diag(z) if m.coupling[h] is None else m.explicit_impedance(h, omega, z)   # all modes explicit
            A = Z + mh.Psi.conj().T @ (stiffness[:, None] * mh.Psi)
            eta = np.linalg.lstsq(A, m.gamma * mh.f, rcond=None)[0] if np.any(mh.f) else \
                np.zeros(z.size, complex)
            etas.append(eta)
            dh = mh.Psi @ eta
            if h == 0:
                d[0] = dh.real
            else:
                d[2 * h - 1], d[2 * h] = dh.real, -dh.imag
        return m.pack(d, etas)
