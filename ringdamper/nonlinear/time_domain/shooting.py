"""Time-domain reference for the EPMC: shooting on the autonomous system (no harmonic balance).

    M q̈ + (C − ξ M) q̇ + K q + Bᵀ (λ(q, w) − λ_static) = 0,      ξ = 2 ζ ω,

with the 3-D Jenkins element of :mod:`ringdamper.nonlinear.contact.friction` (normal spring
``N = max(0, N0 + kn (d_n − gap))``, per tangential direction a spring ``kt`` in series with a
Coulomb slider ``w``, slip limit ``μ N``). ``q`` is measured from the static equilibrium, where
``λ_static = (N0, 0, 0)`` is balanced by the static loads (as in the HBM). ``C`` is the structure's
own damping (:meth:`Structure.damping_matrix`, zero if it has none), as in the EPMC.

Integrator (fixed step ``Δt = T / n_steps``, ``T = 2π/ω``): classical RK4 on ``(q, q̇)`` with the
slider frozen at its value ``w_k`` at the step start and the force of each stage taken through
the play operator, ``T_j = kt (d_j − clip(w_k, d_j − r, d_j + r))``, ``r = μN/kt`` (the exact
Jenkins force while ``d`` moves monotonically within the step); after the step the slider is
updated, ``w_{k+1} = clip(w_k, d_{k+1} − r_{k+1}, d_{k+1} + r_{k+1})``. RK4 is fourth order between
stick/slip events; the kink of the force at a stick→slip event and the slider missing the turning
point of ``d`` inside a reversal step (``O(Δt²)``) make the scheme second order globally
(measured in ``docs/nonlinear_core.md`` §4.4).

Shooting: unknowns ``u = [q0, q̇0, w0, ω, ξ]``; equations: periodicity ``x(T) − x(0) = 0`` of the
state ``x = [q, q̇, w]``, the EPMC amplitude condition ``½ log(Q_1ᴴ M Q_1) − log α = 0`` on the
fundamental ``Q_1 = (2/T) ∫ q e^{−iωt} dt`` (rectangle rule on the step samples, exact to the
order of the scheme for a periodic signal) and the phase condition ``gᵀ b_1 = 0`` (the sine
coefficient of the coordinate ``gᵀ q`` vanishes, as in
:class:`~ringdamper.nonlinear.harmonic_balance.epmc.EPMCProblem`).
Newton with the exact Jacobian of the discrete map (forward tangent propagation through the RK4
stages and the clips; ``Δt`` depends on ω). A pair that sticks through the whole period leaves its
slider undetermined (any position inside its band is periodic); the Newton step is the
minimum-norm least-squares solution, which keeps it where it starts.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ringdamper.nonlinear.contact.friction import FrictionContacts, contact_aft
from ringdamper.nonlinear.fourier import Fourier
from ringdamper.nonlinear.harmonic_balance.epmc import Backbone
from ringdamper.nonlinear.harmonic_balance.structure import Structure

RK4_NODES = (0.0, 0.5, 0.5, 1.0)
RK4_WEIGHTS = np.array([1.0, 2.0, 2.0, 1.0]) / 6.0


class JenkinsTimeModel:
    """Right-hand side and slider update of the EPMC equation with Jenkins contacts (module
    docstring) for a non-cyclic :class:`Structure` (real ``M``, ``K``, ``B``)."""

    def __init__(self, structure: Structure, contacts: FrictionContacts):
        if structure.n_sectors is not None:
            raise ValueError("structure: the time-domain model needs a non-cyclic (real) structure")
        if contacts.law != "jenkins":
            raise ValueError(f"contacts.law must be 'jenkins' for the time-domain model, got "
                             f"{contacts.law!r}")
        contacts = contacts.for_pairs(structure.npairs)
        hd = structure.harmonics[0]
        self.M, self.K = np.asarray(hd.M, float), np.asarray(hd.K, float)
        self.n, self.npairs = self.M.shape[0], contacts.npairs
        B = np.asarray(hd.B, float).reshape(self.npairs, 3, self.n)
        self.Bn, self.Bt = B[:, 0], B[:, 1:]                  # (np, n), (np, 2, n)
        self.c = contacts
        self.MinvK = np.linalg.solve(self.M, self.K)
        C = structure.damping_matrix(0)                       # the structure's own damping, if any
        self.MinvC = np.zeros_like(self.M) if C is None else np.linalg.solve(self.M, np.real(C))
        self.MinvBT = np.linalg.solve(self.M, B.reshape(-1, self.n).T).reshape(self.n, -1, 3)
        self.static = contacts.static_force()[:, 0]
        self.nx = 2 * self.n + 2 * self.npairs                # state [q, q̇, w]

    def _normal(self, q):
        c = self.c
        N = c.N0 + c.kn * (self.Bn @ q - c.gap)
        closed = N > 0
        return np.where(closed, N, 0.0), closed

    def force(self, q, w, derivative: bool = False):
        """Contact force ``M⁻¹Bᵀ(λ − λ_static)`` at displacement ``q`` with the slider ``w``
        ``(np, 2)`` of the step start, and (``derivative``) its Jacobians w.r.t. ``q`` and ``w``."""
        c = self.c
        N, closed = self._normal(q)
        r = (c.mu * N / c.kt)[:, None]
        d = self.Bt @ q                                       # (np, 2)
        lo, hi = d - r, d + r
        below, above = w < lo, w > hi
        T = np.where(below, c.mu[:, None] * N[:, None], np.where(above, -c.mu[:, None] * N[:, None],
                                                                c.kt[:, None] * (d - w)))
        lam = np.concatenate([(N - self.static)[:, None], T], axis=1)          # (np, 3)
        f = np.einsum("npk,pk->n", self.MinvBT, lam)
        if not derivative:
            return f
        dN = (c.kn * closed)[:, None] * self.Bn                                # (np, n)
        sgn = below.astype(float) - above.astype(float)                        # slip ±, stick 0
        stick = ~(below | above)
        dT = (sgn * c.mu[:, None])[:, :, None] * dN[:, None, :] \
            + (stick * c.kt[:, None])[:, :, None] * self.Bt                     # (np, 2, n)
        dlam = np.concatenate([dN[:, None, :], dT], axis=1)                    # (np, 3, n)
        f_q = np.einsum("npk,pkm->nm", self.MinvBT, dlam)
        f_w = -self.MinvBT[:, :, 1:] * (stick * c.kt[:, None])[None]           # (n, np, 2)
        return f, f_q, f_w.reshape(self.n, -1)

    def slider_update(self, q, w, derivative: bool = False):
        """Play operator ``clip(w, d − r, d + r)`` at the step end, and its Jacobians w.r.t. ``q``
        (``(2np, n)``) and ``w`` (diagonal, ``(2np,)``)."""
        c = self.c
        N, closed = self._normal(q)
        r = (c.mu * N / c.kt)[:, None]
        d = self.Bt @ q
        lo, hi = d - r, d + r
        below, above = w < lo, w > hi
        new = np.where(below, lo, np.where(above, hi, w))
        if not derivative:
            return new
        dr = (c.mu * c.kn * closed / c.kt)[:, None] * self.Bn                  # (np, n)
        sgn = below.astype(float) - above.astype(float)
        dq = (below | above)[:, :, None] * self.Bt - sgn[:, :, None] * dr[:, None, :]
        return new, dq.reshape(-1, self.n), (~(below | above)).astype(float).ravel()


@dataclass
class PeriodMap:
    """One period marched from ``x0``: end state ``x`` (``[q, q̇, w]``), the fundamental's cosine
    and sine coefficients ``a``, ``b`` of ``q``, and (if asked) their Jacobians w.r.t.
    ``u = [x0, ω, ξ]``."""

    x: np.ndarray
    a: np.ndarray
    b: np.ndarray
    dx: np.ndarray | None = None
    da: np.ndarray | None = None
    db: np.ndarray | None = None


def march(model: JenkinsTimeModel, x0: np.ndarray, omega: float, xi: float, n_steps: int,
          tangent: bool = False) -> PeriodMap:
    """Integrate one period ``2π/ω`` with ``n_steps`` RK4 steps (module docstring); ``tangent``
    also propagates ``∂x/∂u``."""
    if n_steps < 8:
        raise ValueError(f"n_steps must be >= 8, got {n_steps}")
    if not (np.isfinite(omega) and omega > 0):
        raise ValueError(f"omega must be positive and finite, got {omega}")
    n, nx = model.n, model.nx
    m = nx + 2
    dt = 2.0 * np.pi / (omega * n_steps)
    ddt = np.zeros(m)
    ddt[nx] = -dt / omega
    x = np.asarray(x0, float).copy()
    S = np.eye(nx, m) if tangent else None
    phase = 2.0 * np.pi * np.arange(n_steps) / n_steps
    cos, sin = np.cos(phase) * 2.0 / n_steps, np.sin(phase) * 2.0 / n_steps
    a, b = np.zeros(n), np.zeros(n)
    da = np.zeros((n, m)) if tangent else None
    db = np.zeros((n, m)) if tangent else None
    for k in range(n_steps):
        a += cos[k] * x[:n]
        b += sin[k] * x[:n]
        if tangent:
            da += cos[k] * S[:n]
            db += sin[k] * S[:n]
        x, S = _step(model, x, S, xi, dt, ddt)
    return PeriodMap(x=x, a=a, b=b, dx=S, da=da, db=db)


def _step(model: JenkinsTimeModel, x, S, xi, dt, ddt):
    """One RK4 step of ``(q, q̇)`` with the slider frozen, then the slider update; with the
    tangent ``S = ∂x/∂u`` (None: values only) propagated through the stages (``ddt = ∂Δt/∂u``)."""
    n, nx = model.n, model.nx
    w = x[2 * n:].reshape(-1, 2)
    ks, dks = [], []
    for node in RK4_NODES:
        X = x[:2 * n] + node * dt * ks[-1] if ks else x[:2 * n]
        qs, vs = X[:n], X[n:]
        if S is None:
            f = model.force(qs, w)
        else:
            f, f_q, f_w = model.force(qs, w, True)
            dX = S[:2 * n] + node * (dt * dks[-1] + np.outer(ks[-1], ddt)) if dks else S[:2 * n]
            dk = np.empty_like(dX)
            dk[:n] = dX[n:]
            dk[n:] = -(model.MinvK + f_q) @ dX[:n] + xi * dX[n:] - model.MinvC @ dX[n:] - f_w @ S[2 * n:]
            dk[n:, nx + 1] += vs                                  # ∂/∂ξ
            dks.append(dk)
        ks.append(np.concatenate([vs, -model.MinvK @ qs - f + xi * vs - model.MinvC @ vs]))
    incr = sum(c * k for c, k in zip(RK4_WEIGHTS, ks))
    qv = x[:2 * n] + dt * incr
    if S is None:
        return np.concatenate([qv, model.slider_update(qv[:n], w).ravel()]), None
    dqv = S[:2 * n] + dt * sum(c * dk for c, dk in zip(RK4_WEIGHTS, dks)) + np.outer(incr, ddt)
    w_new, s_q, s_w = model.slider_update(qv[:n], w, True)
    return (np.concatenate([qv, w_new.ravel()]),
            np.vstack([dqv, s_q @ dqv[:n] + s_w[:, None] * S[2 * n:]]))


@dataclass
class ShootingResult:
    """Periodic EPMC solution found by shooting: ``omega`` [rad/s], ``xi`` [1/s], ``zeta``, the
    initial state ``x0 = [q0, q̇0, w0]``, Newton ``iterations``, the final scaled residual
    ``residual`` (max norm) and the step count ``n_steps`` per period."""

    omega: float
    xi: float
    zeta: float
    x0: np.ndarray
    iterations: int
    residual: float
    n_steps: int


def shooting_residual(model, u, alpha, g, n_steps, jacobian=True):
    """``[x(T) − x0; ½ log(aᵀMa + bᵀMb) − log α; gᵀb]`` of ``u = [x0, ω, ξ]`` and its Jacobian."""
    nx = model.nx
    pm = march(model, u[:nx], u[nx], u[nx + 1], n_steps, tangent=jacobian)
    Ma, Mb = model.M @ pm.a, model.M @ pm.b
    n2 = pm.a @ Ma + pm.b @ Mb
    r = np.r_[pm.x - u[:nx], 0.5 * np.log(n2) - np.log(alpha), g @ pm.b]
    if not jacobian:
        return r, None
    J = np.vstack([pm.dx - np.eye(nx, nx + 2), (Ma @ pm.da + Mb @ pm.db) / n2, g @ pm.db])
    return r, J


def shoot(structure: Structure, contacts: FrictionContacts, alpha: float, x0: np.ndarray,
          omega: float, xi: float, g: np.ndarray, n_steps: int = 2048, tol: float = 1e-10,
          max_iter: int = 30) -> ShootingResult:
    """Newton shooting for the EPMC solution of modal amplitude ``alpha`` from the guess
    ``(x0, ω, ξ)`` (e.g. :func:`hbm_state`), phase row ``g`` (:func:`phase_row`). Converged when
    the scaled residual (periodicity by ``max|q0|`` and ``ω max|q0|``, amplitude in log, phase by
    ``max|q0|``) is below ``tol`` and the scaled Newton step below ``√tol``; raises
    ``RuntimeError`` otherwise (also if ω leaves the positive axis)."""
    if not alpha > 0:
        raise ValueError(f"alpha must be positive, got {alpha}")
    model = JenkinsTimeModel(structure, contacts)
    n, nx = model.n, model.nx
    u = np.r_[np.asarray(x0, float), omega, xi]
    if u.size != nx + 2:
        raise ValueError(f"x0 must have {nx} entries [q, q̇, w], got {u.size - 2}")
    for it in range(1, max_iter + 1):
        r, J = shooting_residual(model, u, alpha, g, n_steps)
        sq = max(np.max(np.abs(u[:n])), 1e-300)
        su = np.r_[np.full(n, sq), np.full(n, sq * u[nx]), np.full(nx - 2 * n, sq),
                   u[nx], u[nx]]
        sr = np.r_[su[:nx], 1.0, sq]
        Js = J * su[None, :] / sr[:, None]
        step = np.linalg.lstsq(Js, -r / sr, rcond=1e-10)[0]
        u = u + step * su
        res = np.max(np.abs(r / sr))
        if not u[nx] > 0:
            raise RuntimeError(f"shooting diverged: ω = {u[nx]:.3g} after {it} iterations "
                               f"(residual {res:.2e})")
        if res < tol and np.max(np.abs(step)) < tol ** 0.5:
            r = shooting_residual(model, u, alpha, g, n_steps, jacobian=False)[0]
            res = np.max(np.abs(r / sr))
            return ShootingResult(omega=u[nx], xi=u[nx + 1], zeta=u[nx + 1] / (2 * u[nx]),
                                  x0=u[:nx], iterations=it, residual=res, n_steps=n_steps)
    raise RuntimeError(f"shooting did not converge in {max_iter} iterations (residual {res:.2e})")


def hbm_state(backbone: Backbone, contacts: FrictionContacts, i: int, nt: int = 4096):
    """Initial state ``x0 = [q(0), q̇(0), w(0)]``, ω and ξ of grid point ``i`` of an EPMC
    backbone: ``q`` and ``q̇`` from its harmonics ``Q_h = Φ_h η_h`` at ``t = 0``, the slider from
    the periodic play operator on its contact displacements sampled at ``nt`` points."""
    model, omega = backbone.model, backbone.omega[i]
    H = backbone.H
    Q = [model.modal[h].Phi @ backbone.eta[h][i] for h in range(H + 1)]
    q0 = sum(Qh.real for Qh in Q)
    v0 = sum((1j * h * omega * Q[h]).real for h in range(1, H + 1))
    d = backbone.d[i].reshape(model.C, model.npairs, 3).transpose(1, 2, 0)
    w0 = contact_aft(contacts, Fourier(H, nt), d, jacobian=False).memory
    return np.r_[q0, v0, w0.ravel()], omega, backbone.xi[i]


def phase_row(backbone: Backbone) -> np.ndarray:
    """Row ``g`` with ``gᵀ Q_1`` the coordinate whose sine coefficient the EPMC's phase condition
    sets to zero: a contact coordinate (row of ``B``) or an explicit mode (``φ_kᵀ M``)."""
    model = backbone.model
    k = backbone.phase_index
    hd = model.structure.harmonics[1]
    if k < model.n_d:
        return np.real(hd.B[k - model.slot_index(1, True, 0)])
    mode = model.S[1][k - model.eta_index(1, 0, True)]
    return np.real(hd.M @ model.modal[1].Phi[:, mode])


def return_error(structure: Structure, contacts: FrictionContacts, x0: np.ndarray, omega: float,
                 xi: float, n_steps: int = 2048) -> float:
    """``max|x(T) − x(0)|`` of ``[q, q̇/ω]`` over one period from ``x0`` with ω, ξ, relative to
    ``max|q(0)|, |q̇(0)/ω|`` (the periodicity check of an HBM solution)."""
    model = JenkinsTimeModel(structure, contacts)
    n = model.n
    x = march(model, x0, omega, xi, n_steps).x
    scale = np.r_[np.ones(n), np.full(n, 1.0 / omega)]
    err = (x[:2 * n] - x0[:2 * n]) * scale
    return float(np.max(np.abs(err)) / np.max(np.abs(x0[:2 * n] * scale)))
