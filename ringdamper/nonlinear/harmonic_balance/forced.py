"""Forced-response harmonic balance (paper Eq. 1; docs/design.md §3.5):

    M q̈ + C q̇ + K q + Bᵀ λ(Bq) = Re(γ F̂_h e^{ihωt}),

with structural modal damping ``C`` (ratio ζ_s, or the structure's ``C``), condensed as in
:mod:`ringdamper.nonlinear.harmonic_balance.condensed` (ξ = 0). Unknowns ``z = [y, ω]``.

The Jacobian is returned as an operator (:class:`ringdamper.nonlinear.harmonic_balance.condensed.CoreJacobian`
bordered by the ω column, :mod:`ringdamper.nonlinear.solvers.jacobian`), as the EPMC's: Newton forms it
when it factorises, and the continuation's tangents are solved by GMRES on the corrector's last LU
(:class:`ringdamper.nonlinear.solvers.krylov.LaggedSolver`) instead of a factorisation each.
"""
from __future__ import annotations

import numpy as np

from ringdamper.nonlinear.harmonic_balance.condensed import CondensedHBM, CoreEval, GaugeState
from ringdamper.nonlinear.solvers.jacobian import Evaluation, bordered


class ForcedProblem:
    """One forced-response solve: residual of ``z = [y, ω]`` (one equation fewer than unknowns: the
    continuation closes it) on the condensed ``model`` (fixed), in the solve's gauge state ``gauge``
    (default the model's initial one), which every evaluation, accepted point (:meth:`accept`) and
    failed step (:meth:`on_failure`) replaces by the state it returns, as in
    :class:`ringdamper.nonlinear.harmonic_balance.epmc.EPMCProblem`."""

    def __init__(self, model: CondensedHBM, gauge: GaugeState | None = None):
        if not model.forced:
            raise ValueError("the condensed model must be built with forced=True")
        self.model = model
        self.gauge = model.initial_gauge() if gauge is None else gauge

    def fun(self, z: np.ndarray, jacobian: bool = True) -> Evaluation:
        ev = self.evaluate(z[:-1], z[-1], jacobian)
        J = bordered(ev.J, ev.dr_domega) if jacobian else None
        return Evaluation(ev.r, J, ev.trivial, self.model.n_core, ev)

    def at_frequency(self, omega: float):
        """Residual of ``y`` alone at fixed ω (square)."""
        def fun(y, jacobian=True):
            ev = self.evaluate(y, omega, jacobian)
            return Evaluation(ev.r, ev.J, ev.trivial, self.model.n_core, ev)
        return fun

    def evaluate(self, y: np.ndarray, omega: float, jacobian: bool) -> CoreEval:
        """The model's evaluation at ``(y, ω)`` (ξ = 0) in the solve's gauge state, which takes the state
        after it."""
        ev = self.model.evaluate(y, omega, 0.0, self.gauge, jacobian)
        self.gauge = ev.state
        return ev

    def accept(self, z: np.ndarray, ev: CoreEval) -> None:
        """The accepted point ``z = [y, ω]`` (evaluated as ``ev``): the gauge state after it."""
        self.gauge = self.model.accepted(self.gauge, z[:-1], ev)

    def on_failure(self) -> bool:
        """After a failed step: pin the rigid-body directions whose hold was lost on the way; True if
        that changed the problem (retry the step)."""
        self.gauge, added = self.gauge.pin_seen()
        return added

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
