"""Damped nonlinear normal modes by the extended periodic motion concept (Krack 2015; paper §2.5.3;
docs/design.md §3.4).

    M q̈ + (C − ξ M) q̇ + K q + Bᵀ λ(Bq) = 0,       ξ = 2 ζ ω,

with ``C`` the structure's own damping (matrix or modal ratios, :mod:`ringdamper.nonlinear.harmonic_balance.structure`;
absent in the campaign, whose structural damping enters the E-EBM only). The artificial negative
damping acts on the mass matrix (Krack's definition), so ``ξ`` balances every dissipation over a
period, ``ξ ∫ q̇ᵀ M q̇ dt = ∫ q̇ᵀ C q̇ dt + ∮ λ · dd``, and ``ζ`` is the total damping ratio. For a linear
system with modal damping ``c_r = 2 ζ_r ω_r`` the solution is the mode itself: ``ω = ω_r`` (the
undamped natural frequency, ``|λ|`` of the eigenvalue ``λ = −ζ_r ω_r ± i ω_r √(1 − ζ_r²)``) and ``ζ = ζ_r``.

solved by harmonic balance (condensed, :mod:`ringdamper.nonlinear.harmonic_balance.condensed`) with unknowns
``z = [y, ω, ξ]`` and two extra equations:

* amplitude: ``½ log(Q_1ᴴ M_1 Q_1) − log α = 0`` (fundamental harmonic mass-normalised,
  ``Q_h = α ψ_h`` with ``ψ_1ᴴ M_1 ψ_1 = 1``; ``Q_1ᴴ M_1 Q_1 = Σ_r |η_{1,r}|²``: α is the *modal
  amplitude*, the campaign's), or, with ``amplitude = w`` (a DoF as a unit row, or any combination
  of DoFs), ``log |w Q_1| − log α = 0``: α is the amplitude of harmonic 1 of ``w q``;
* phase: the sine slot of harmonic 1 of one unknown (the largest of the linear mode's contact
  coordinates, or explicit modal coordinates) is zero.

Continuation in ``s = log α`` lands on every value of the requested α grid (so outputs on the
common grid are converged solutions, not interpolants). The start is the linearised stuck mode
(contact springs ``(kn, kt, kt)`` on preloaded pairs, :meth:`Structure.stuck_modes`).

A solve is an :class:`EPMCProblem`: the condensed model (fixed, shared by every solve on it) and the
solve's own gauge state (:class:`ringdamper.nonlinear.harmonic_balance.condensed.GaugeState`), which its evaluations,
accepted points and failed steps replace. :meth:`Backbone.problem` is the problem of one point of a
backbone, to restart from it; :func:`resolve_point` and :func:`continue_point` solve a point again at
another truncation or amplitude.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field, replace

import numpy as np

from ringdamper.nonlinear.contact.elements import Elements
from ringdamper.nonlinear.contact.friction import FrictionContacts
from ringdamper.nonlinear.fourier import default_nt
from ringdamper.nonlinear.harmonic_balance.condensed import (
    CondensedHBM,
    GaugeState,
    pole_modes,
    squared_amplitude,
    structural_damping,
)
from ringdamper.nonlinear.harmonic_balance.structure import Structure
from ringdamper.nonlinear.solvers.continuation import (
    ContinuationPoint,
    NaturalResult,
    StepControl,
    natural_then_arclength,
)
from ringdamper.nonlinear.solvers.jacobian import Evaluation, bordered
from ringdamper.nonlinear.solvers.newton import newton
from ringdamper.status import Status


@dataclass
class Backbone:
    """dNNM on the α grid. Per α: ``omega`` [rad/s], ``xi`` [1/s], ``zeta``, ``status`` (0 =
    converged, see :class:`Status`), ``reason``, Newton ``iterations``, contact displacement and
    force slots ``d``, ``lam`` ``(nα, C, p)``, modal coordinates ``eta[h]`` ``(nα, m_h)`` of all
    modes, ``pinned`` the rigid-body directions gauged at each point and
    ``drift`` (largest dropped rigid-body equilibrium, see the gauge). ``branch``
    holds every accepted continuation point ``(α, ω, ξ)``; ``model`` the condensed HBM and
    ``phase_index`` the unknown fixed by the phase condition (what :meth:`problem` needs to restart
    from a point), ``pole_window`` the ``(lo, hi)`` band of
    :func:`pole_modes` that chose its explicit modes and ``drift_tol`` the DRIFT limit (what
    :func:`resolve_point` needs to build the same problem at another H); ``amplitude`` the row
    ``w`` whose harmonic-1 amplitude α is (None: the modal amplitude); ``condition`` the κ₁
    estimate of each point's equilibrated Jacobian where the continuation factorised it
    (:class:`ringdamper.nonlinear.solvers.continuation.ContinuationPoint`; NaN elsewhere, None: none)."""

    alpha: np.ndarray
    omega: np.ndarray
    xi: np.ndarray
    zeta: np.ndarray
    status: np.ndarray
    reason: list
    iterations: np.ndarray
    d: np.ndarray
    lam: np.ndarray
    eta: list
    pinned: list
    drift: np.ndarray
    branch: np.ndarray
    model: CondensedHBM = field(repr=False)
    phase_index: int = -1
    wall_time: float = 0.0
    pole_window: tuple = (0.0, 0.0)
    drift_tol: float = 1e-8
    amplitude: np.ndarray | None = None
    condition: np.ndarray | None = None

    def unknowns(self, i: int) -> np.ndarray:
        """Unknown vector ``z = [y, ω, ξ]`` of grid point ``i``."""
        y = self.model.pack(self.d[i], [e[i] for e in self.eta])
        return np.r_[y, self.omega[i], self.xi[i]]

    def problem(self, i: int) -> "EPMCProblem":
        """The EPMC problem of grid point ``i`` on the backbone's model, in the gauge state that point was
        solved in (its pinned rigid-body directions, reference its zero-mode positions): a restart from
        :meth:`unknowns` reproduces it."""
        return EPMCProblem(self.model, self.phase_index, self.drift_tol, self.amplitude,
                           gauge=self.model.gauge_at(self.unknowns(i), self.pinned[i]))

    @property
    def H(self) -> int:
        return self.model.H

    def harmonics(self, i: int) -> list:
        """Harmonics ``Q_h = Φ_h η_h`` (complex, ``h = 0..H``, convention of
        :mod:`ringdamper.nonlinear.fourier`) of every DoF at grid point ``i``."""
        return [m.Phi @ e[i] for m, e in zip(self.model.modal, self.eta)]

    @property
    def nt(self) -> int:
        return self.model.fourier.nt


class EPMCProblem:
    """One EPMC solve (a :class:`ringdamper.nonlinear.solvers.continuation.ParameterProblem`): residual
    ``[r_core; amplitude; phase]`` of ``z = [y, ω, ξ]`` at ``s = log α`` on the condensed ``model``
    (fixed, may be shared), in the solve's gauge state ``gauge`` (default the model's
    :meth:`~ringdamper.nonlinear.harmonic_balance.condensed.CondensedHBM.initial_gauge`).
    ``gauge`` is the one thing that changes: every evaluation (:meth:`fun`), accepted point
    (:meth:`accept`) and failed step (:meth:`on_failure`) replaces it by the state it returns. ``amplitude``: the
    row ``w`` (n,) whose harmonic-1 amplitude α is, None for the modal amplitude."""

    def __init__(self, model: CondensedHBM, phase_index: int, drift_tol: float = 1e-8,
                 amplitude: np.ndarray | None = None, gauge: GaugeState | None = None):
        self.model, self.phase_index, self.drift_tol = model, phase_index, drift_tol
        self.amplitude = amplitude
        self.row = None if amplitude is None else amplitude @ model.modal[1].Phi     # ρ = w Φ_1
        self.n = model.n_core + 2
        self.gauge = model.initial_gauge() if gauge is None else gauge
        self.jump_mask = self._jump_mask()

    def fun(self, z: np.ndarray, s: float, jacobian: bool = True) -> Evaluation:
        m = self.model
        y, omega, xi = z[:-2], z[-2], z[-1]
        ev = m.evaluate(y, omega, xi, self.gauge, jacobian)
        self.gauge = ev.state
        n2 = squared_amplitude(ev.eta[1], self.row)
        r = np.concatenate((ev.r, (0.5 * np.log(n2) - s, y[self.phase_index])))
        if not jacobian:
            return Evaluation(r, None, None, m.n_core, ev)
        n2, g, d_w, d_x = m.amplitude2(ev, omega, xi, self.row)
        amplitude = np.concatenate((g, (d_w, d_x))) / (2 * n2)
        phase = np.zeros(self.n)
        phase[self.phase_index] = 1.0
        J = bordered(ev.J, np.c_[ev.dr_domega, ev.dr_dxi], np.vstack([amplitude, phase]))
        return Evaluation(r, J, ev.trivial, m.n_core, ev)

    def dfun_ds(self, z, s):
        e = np.zeros(self.n)
        e[-2] = -1.0
        return e

    def scale(self, z: np.ndarray) -> np.ndarray:
        """Convergence scales: :meth:`CondensedHBM.core_scale` for ``y``, ω for ω and ξ."""
        return np.concatenate((self.model.core_scale(z[:-2]), (abs(z[-2]), abs(z[-2]))))

    def accept(self, z, ev) -> None:
        """The accepted point ``z`` (evaluated as ``ev``): the gauge state after it
        (:meth:`ringdamper.nonlinear.harmonic_balance.condensed.CondensedHBM.accepted`)."""
        self.gauge = self.model.accepted(self.gauge, z[:-2], ev)

    def _jump_mask(self) -> np.ndarray:
        """Unknowns of the branch-jump test: all but the mean (harmonic-0) contact slots and
        rigid-body/explicit modal coordinates. Where the last pairs holding the ring's rigid
        motion let go, its mean position (and with it every DC slot) moves by much more than the
        predictor for a tiny change of α while ω, ξ and the harmonics change smoothly; a switch
        to another branch shows in those."""
        m = self.model
        mask = np.ones(self.n, bool)
        mask[:m.p] = False                                  # slot 0 (mean) of every coordinate
        mask[m.eta_slices[0]] = False
        return mask

    def on_failure(self) -> bool:
        """After a failed step: pin the rigid-body directions whose hold was lost on the way
        (:meth:`ringdamper.nonlinear.harmonic_balance.condensed.GaugeState.pin_seen`); True if that changed the problem
        (retry the step)."""
        self.gauge, added = self.gauge.pin_seen()
        return added


#: fresh Jacobians a corrector of the EPMC continuation may use before its step is rejected and halved
#: (``max_iter`` still bounds the start point and the grid solves). Measured (docs/nonlinear_core.md
#: §4.1): a corrector that converges takes 0–2 fresh Jacobians on nine steps in ten, one that fails
#: cycles between contact states for all of ``max_iter``; 6 cost least over the hard rings (10 did not).
CORRECTOR_JACOBIANS = 6


#: corrector tolerance of the continuation points between grid values (:meth:`StepControl.corrector_tolerance`)
BETWEEN_TOL = 1e-5


def default_steps() -> StepControl:
    """Step control of the EPMC in ``log α``: initial 0.2, minimum 1e-4, maximum 0.5, correctors failed
    after :data:`CORRECTOR_JACOBIANS` fresh Jacobians, quasi-Newton corrector steps (on sixteen
    campaign and paper rings 10 % less CPU and 14 % fewer LUs than chord steps:
    docs/nonlinear_core.md §10)."""
    return StepControl(initial=0.2, minimum=1e-4, maximum=0.5, corrector=CORRECTOR_JACOBIANS,
                       between=BETWEEN_TOL, quasi_newton=True)


def epmc(structure: Structure, contacts: FrictionContacts | Elements, alpha, *, H: int = 1,
         nt: int | None = None, mode: int = 0, omega_target: float | None = None,
         pole_band: float = 0.1, tol: float = 1e-8, max_iter: int = 20,
         steps: StepControl | None = None, gauge_reference: np.ndarray | None = None,
         alpha_start: float | None = None, drift_tol: float = 1e-8,
         stuck_shortcut: bool = True, max_arc_points: int | None = None,
         amplitude: np.ndarray | None = None, nonlinear_rows: bool = False) -> Backbone:
    """dNNM backbone of one mode over the increasing amplitude grid ``alpha``: modal amplitudes, or
    with ``amplitude = w`` (n,), amplitudes of harmonic 1 of ``w q`` (a DoF: a unit row; a relative
    displacement: a difference of two; module docstring).

    ``mode``/``omega_target``: which linearised stuck mode of harmonic 1 to follow (index in
    ascending frequency, or the one closest to ``omega_target`` [rad/s]). ``pole_band``: modes of
    harmonic ``h`` whose ω_r lies within ``±pole_band·hω₀`` of ``hω₀`` (ω₀ the stuck frequency;
    low side widened to ``(1 − 2·pole_band)``) are kept explicit. ``steps``: control in ``log α``
    (default :func:`default_steps`). ``gauge_reference``: position of zero modes while
    they are undetermined at the first point (default 0). ``stuck_shortcut``: the grid points
    below the stick limit of the linear stuck mode (:func:`stick_limit`) are that mode scaled by α,
    without Newton (:func:`_stuck_points`). ``alpha_start``: where the continuation of the other
    grid points starts from the linear stuck mode (default: half the stick limit, or half
    :func:`linear_limit` where the stick limit is zero, if below the first of those points; started
    just below the stick limit, the first step crosses the stick-slip corner along the linear
    branch's tangent, and on the cyclic test system of ``tests/nonlinear/test_cyclic.py`` the
    continuation then ran out of points at 0.99 of the limit and converged at 0.9 or below).
    ``drift_tol``: relative size of the dropped rigid-body equilibrium above which a converged
    point gets status DRIFT.
    ``max_arc_points``: arc-length points allowed past a fold in α (default
    :meth:`ringdamper.nonlinear.solvers.continuation.StepControl.arc_points`). ``tol`` and ``max_iter`` are the
    Newton settings of every solve (they replace those of ``steps``). ``nonlinear_rows``: the Newton
    systems are solved on the nonlinear contact rows where that system is the smaller
    (:mod:`ringdamper.nonlinear.harmonic_balance.nonlinear_rows`; undamped structures).
    The condensed model's receptance series are formed about the frequency the first Newton solve
    starts from (:class:`ringdamper.nonlinear.harmonic_balance.condensed.CondensedHBM`, ``expansion``).
    """
    t0 = time.perf_counter()
    alpha = np.asarray(alpha, float)
    if alpha.ndim != 1 or np.any(np.diff(alpha) <= 0) or alpha[0] <= 0:
        raise ValueError("alpha must be a positive, strictly increasing 1-D grid")
    if H < 1:
        raise ValueError("the EPMC needs H >= 1")
    nt = default_nt(H) if nt is None else nt
    steps = replace(steps or default_steps(), tol=tol, max_iter=max_iter, max_points=max_arc_points)
    contacts = contacts.for_pairs(structure.npairs)
    omega0, xi0, phi = _stuck_mode(structure, contacts, mode, omega_target)
    phi = phi / _measure_of_mode(structure, amplitude, phi)     # unit amplitude in the grid's measure
    window = (omega0 * (1 - 2 * pole_band), omega0 * (1 + pole_band))
    onset = stick_limit(structure, contacts, phi)
    below_onset = alpha[alpha < (1 - 1e-9) * onset] if stuck_shortcut else alpha[:0]
    model = CondensedHBM(structure, contacts, H, nt, explicit=pole_modes(structure, H, *window),
                         damping=structural_damping(structure, H),
                         expansion=(omega0, 0.0 if below_onset.size else xi0),   # the first Newton's start
                         nonlinear_rows=nonlinear_rows)
    gauge = model.initial_gauge(None if gauge_reference is None else np.asarray(gauge_reference, float))
    _, phase_index = _initial_guess(model, phi, omega0, 1.0, reference=gauge.reference)
    problem = EPMCProblem(model, phase_index, drift_tol, amplitude, gauge=gauge)
    stuck = _stuck_points(problem, phi, omega0, below_onset)
    rest = alpha[len(stuck):]
    run = None
    if rest.size:
        if alpha_start is None:
            alpha_start = min(rest[0], 0.5 * (onset if onset > 0 else linear_limit(structure, contacts, phi)))
        z0, _ = _initial_guess(model, phi, omega0, alpha_start, xi0, reference=problem.gauge.reference)
        run = natural_then_arclength(problem, z0, np.log(rest), steps, s_start=np.log(alpha_start))
    return _collect(_joined(stuck, run, np.log(alpha)), model, alpha, problem, time.perf_counter() - t0,
                    window)


def _stuck_mode(structure, contacts, mode, omega_target):
    """The mode the continuation starts from, ``(ω₀, ξ₀, φ)``: the linearised stuck mode (ξ₀ = 0), or,
    for forces that depend on velocity (a damper at rest, e.g. tanh friction holding a light DoF), the
    complex mode of the system linearised at rest with that damping and the structure's,
    ``λ² M φ + λ C φ + K φ = 0``: ``ω₀ = |λ|``, ``ξ₀ = −2 Re λ``, ``φᴴ M φ = 1`` (``mode``: the index in
    ascending ``|λ|`` of the oscillating modes, or the one nearest ``omega_target``; the stuck mode when
    that damping leaves no such mode oscillating)."""
    stiffness = contacts.stuck_stiffness().ravel()
    omegas, Phi = structure.stuck_modes(stiffness, h=1)
    k = mode if omega_target is None else int(np.argmin(np.abs(omegas - omega_target)))
    if not contacts.velocity_dependent:
        return omegas[k], 0.0, Phi[:, k]
    hd = structure.harmonics[1]
    n = hd.M.shape[0]
    K = hd.K + hd.B.conj().T @ (stiffness[:, None] * hd.B)
    C = hd.B.conj().T @ (contacts.rest_damping().ravel()[:, None] * hd.B)
    if structure.damped:
        C = C + structure.damping_matrix(1)
    state = np.block([[np.zeros((n, n)), np.eye(n)], [-np.linalg.solve(hd.M, K), -np.linalg.solve(hd.M, C)]])
    lam, vectors = np.linalg.eig(state)
    oscillating = np.flatnonzero(lam.imag > 0)
    if oscillating.size <= (mode if omega_target is None else 0):     # overdamped at rest: the stuck mode
        return omegas[k], 0.0, Phi[:, k]
    oscillating = oscillating[np.argsort(np.abs(lam[oscillating]))]
    nearest = mode if omega_target is None else int(np.argmin(np.abs(np.abs(lam[oscillating]) - omega_target)))
    k = oscillating[nearest]
    phi = vectors[:n, k]
    phi = phi / np.sqrt(np.real(np.vdot(phi, hd.M @ phi)))
    return abs(lam[k]), -2.0 * lam[k].real, phi


def _measure_of_mode(structure: Structure, amplitude, phi: np.ndarray) -> float:
    """Amplitude ``|w φ|`` of the measure ``w`` on the mass-normalised mode ``φ`` (1 for the modal
    amplitude): ``φ`` divided by it has unit amplitude in the grid's measure (the stick and linear
    limits of that mode are then grid amplitudes). Raises, naming ``amplitude``, for a row of the
    wrong shape or one the mode does not move."""
    if amplitude is None:
        return 1.0
    n = structure.harmonics[1].M.shape[0]
    if np.shape(amplitude) != (n,):
        raise ValueError(f"amplitude: expected a row of shape ({n},) (one weight per DoF), got "
                         f"{np.shape(amplitude)}")
    measure = abs(np.asarray(amplitude) @ phi)
    if not measure > 1e-12 * np.linalg.norm(amplitude) * np.max(np.abs(phi)):
        raise ValueError("amplitude: the followed mode does not move this row (w φ = 0); choose a "
                         "DoF the mode moves, or the modal amplitude (amplitude=None)")
    return float(measure)


def linear_limit(structure, contacts, phi):
    """Smallest modal amplitude at which the linear stuck mode ``phi`` meets a discrete event of the
    nonlinearity (a preloaded pair slipping or opening, a gap closing: ``contacts.linear_limit``)."""
    contacts = contacts.for_pairs(structure.npairs)
    return contacts.linear_limit((structure.harmonics[1].B @ phi).reshape(-1, 3))


def stick_limit(structure, contacts, phi) -> float:
    """Largest modal amplitude up to which the linear stuck mode ``phi`` is an exact solution of the
    nonlinearity at every instant (``contacts.stick_limit`` of the harmonic-1 amplitudes ``c = B₁φ``
    per pair or element; ``inf`` if it always is, 0 if never)."""
    contacts = contacts.for_pairs(structure.npairs)
    return contacts.stick_limit((structure.harmonics[1].B @ phi).reshape(-1, 3))


def _stuck_points(problem: EPMCProblem, phi, omega0: float, alpha) -> list:
    """Solutions at the amplitudes ``alpha`` below the stick limit, without continuation.

    While every pair sticks the EPMC is linear and homogeneous in ``y`` (contact forces ``K_c d``
    about the static state, no gauged direction, the amplitude equation shifts by ``log`` of a
    scale factor): the solution at ``α`` is ``y(α) = (α/α₁) y(α₁)`` at the same ω₀ and ξ = 0.
    ``y(α₁)`` is the linear stuck mode (:func:`_initial_guess`) polished by Newton to 1e-12 (the
    eigenvector of the stuck system and the condensed equations agree to ≈ 1e-9 only). Every
    point is evaluated once for its outputs and checked as Newton checks convergence, tighter:
    the correction ``δz = −J⁻¹ r`` satisfies ``max |δz| / scale ≤ 1e-10``. The Jacobian at ``α``
    is that at ``α₁`` scaled, ``J(α) = S_r J(α₁) S_c`` (``S_r``: the amplitude row by ``α₁/α``;
    ``S_c``: the ω and ξ columns by ``α/α₁``), so one factorisation serves all points. The list
    stops at the first point that fails (the continuation then solves it)."""
    if not alpha.size:
        return []
    a1 = alpha[0]
    z_lin, _ = _initial_guess(problem.model, phi, omega0, a1, reference=problem.gauge.reference)
    first = newton(lambda z, jac: problem.fun(z, np.log(a1), jac), z_lin, problem.scale, 1e-12)
    if not first.converged:
        return []
    out, fac = [], first.factorization
    for a in alpha:
        z = first.z.copy()
        z[:-2] *= a / a1
        evaluation = problem.fun(z, np.log(a), jacobian=False)
        ev = evaluation.payload
        b = -evaluation.r
        b[-2] *= a / a1
        dz = fac.solve(b)
        dz[-2:] *= a1 / a
        if not np.max(np.abs(dz) / problem.scale(z)) <= 1e-10:
            break
        problem.accept(z, ev)
        out.append(ContinuationPoint(np.log(a), z, ev, 0))
    return out


def _joined(stuck: list, run, grid) -> NaturalResult:
    """The stuck points on the first grid values and the continuation ``run`` on the others, as one
    :class:`NaturalResult` on ``grid``; the branch keeps the continuation's points above the last stuck
    one only (it starts below it, at half the stick limit), so it stays ordered in α."""
    k = len(stuck)
    out = NaturalResult(grid, list(stuck) + [None] * (grid.size - k), np.zeros(grid.size, int),
                        [""] * grid.size, list(stuck))
    if run is not None:
        out.points[k:], out.status[k:], out.reason[k:] = run.points, run.status, run.reason
        last = stuck[-1].s if stuck else -np.inf
        out.branch += [p for p in run.branch if p.s > last]
    return out


def resolve_point(backbone: Backbone, i: int, H: int, nt: int | None = None, tol: float = 1e-8,
                  max_iter: int = 20, neighbour: tuple | None = None,
                  models: dict | None = None) -> tuple[Backbone | None, str]:
    """Grid point ``i`` of ``backbone`` solved again at ``H`` harmonics (``nt`` AFT samples, default
    :func:`default_nt`) by Newton at its fixed α: ``(one-point backbone, "")``, or ``(None, why)``
    if Newton does not converge. The problem is the backbone's at ``H`` (same structure, which must
    hold harmonics up to ``H``; same explicit modes of the shared harmonics, phase unknown, gauge
    position and pinned directions); Newton takes quasi-Newton steps on each factorisation, as the
    continuation's correctors (:func:`default_steps`). The start is the point's solution with the
    harmonics above the backbone's set to zero, plus, with ``neighbour = (lower, j, higher)``
    (another grid point: ``lower`` its backbone at this backbone's H, ``j`` its index there,
    ``higher`` its one-point backbone at ``H``), the change that raising H made to that point.
    ``models``: the problems at higher truncations that earlier calls for points of the same backbone
    built, by ``(H, nt)``; the one needed is taken from it or built and added (its receptance series
    formed about this point's start), so that its modal data and receptance series are formed once for
    all points (:class:`ringdamper.nonlinear.harmonic_balance.receptance.Receptance`; the series then serves every point
    within its reach, to rounding). The model is fixed: each point's solve has its own gauge state
    (that of point ``i``: its pinned directions, reference its start's zero-mode positions)."""
    t0 = time.perf_counter()
    nt = default_nt(H) if nt is None else nt
    model = None if models is None else models.get((H, nt))
    if model is None:
        model = _higher_model(backbone, H, nt, _start_frequency(backbone, i, neighbour))
        if models is not None:
            models[H, nt] = model
    z0 = _padded_state(backbone, i, model)
    if neighbour is not None:
        lower, j, higher = neighbour
        z0 += higher.unknowns(0) - _padded_state(lower, j, model)
    phase = _same_unknown(backbone.model, model, backbone.phase_index)
    problem = EPMCProblem(model, phase, backbone.drift_tol, backbone.amplitude,
                          gauge=model.gauge_at(z0, backbone.pinned[i]))
    s = np.log(backbone.alpha[i])
    res = newton(lambda z, jac: problem.fun(z, s, jac), z0, problem.scale, tol, max_iter, quasi_newton=True)
    if not res.converged:
        return None, f"Newton at H = {H}: {res.reason}"
    run = NaturalResult(np.array([s]), [ContinuationPoint(s, res.z, res.payload, res.iterations)],
                        np.zeros(1, int), [""], [])
    return _collect(run, model, backbone.alpha[i:i + 1], problem, time.perf_counter() - t0,
                    backbone.pole_window), ""


def _start_frequency(backbone: Backbone, i: int, neighbour: tuple | None) -> tuple[float, float]:
    """``(ω, ξ)`` of the start of :func:`resolve_point` for point ``i`` (the point's, shifted as its
    neighbour's by raising H, the same arithmetic as the start vector's)."""
    omega, xi = backbone.omega[i], backbone.xi[i]
    if neighbour is not None:
        lower, j, higher = neighbour
        omega, xi = omega + (higher.omega[0] - lower.omega[j]), xi + (higher.xi[0] - lower.xi[j])
    return omega, xi


def _higher_model(backbone: Backbone, H: int, nt: int, expansion: tuple[float, float]) -> CondensedHBM:
    """The problem of ``backbone`` at ``H`` harmonics and ``nt`` AFT samples: same structure and
    contacts, the explicit modes of the backbone's pole window (the same modes of the shared harmonics),
    its receptance series formed about ``expansion = (ω, ξ)``."""
    base = backbone.model
    model = CondensedHBM(base.structure, base.contacts, H, nt,
                         explicit=pole_modes(base.structure, H, *backbone.pole_window),
                         damping=structural_damping(base.structure, H), expansion=expansion,
                         nonlinear_rows=base.stuck is not None)
    if not all(np.array_equal(a, b) for a, b in zip(base.S, model.S)):
        raise ValueError("the explicit modes of the shared harmonics differ between the two truncations")
    return model


def _padded_state(backbone: Backbone, i: int, model: CondensedHBM) -> np.ndarray:
    """Unknowns ``z`` of ``model`` (more harmonics than the backbone's) from point ``i`` of
    ``backbone``, zero in the extra harmonics."""
    d = np.zeros((model.C, model.p))
    d[:backbone.model.C] = backbone.d[i]
    eta = [backbone.eta[h][i] if h <= backbone.H else np.zeros(m.w2.size, complex)
           for h, m in enumerate(model.modal)]
    return np.r_[model.pack(d, eta), backbone.omega[i], backbone.xi[i]]


def continue_point(backbone: Backbone, j: int, alpha: float, tol: float = 1e-8, max_iter: int = 20,
                   steps: StepControl | None = None,
                   max_arc_points: int | None = None) -> tuple[Backbone | None, str]:
    """Continuation at the truncation of ``backbone`` from its grid point ``j`` to the amplitude
    ``alpha`` (above α_j; ``steps`` and ``max_arc_points`` as in :func:`epmc`): ``(one-point
    backbone, "")``, or ``(None, why)`` if it does not get there, or if the branch folds back below
    α_j on the way (a value reached after that lies on another sheet of the branch than point ``j``).
    The problem, gauge position and pinned directions are those of point ``j`` (:meth:`Backbone.problem`);
    the model is shared with ``backbone``."""
    t0 = time.perf_counter()
    model = backbone.model
    z0 = backbone.unknowns(j)
    problem = backbone.problem(j)
    steps = replace(steps or default_steps(), tol=tol, max_iter=max_iter, max_points=max_arc_points)
    run = natural_then_arclength(problem, z0, np.log([alpha]), steps, s_start=np.log(backbone.alpha[j]),
                                 floor=np.log(backbone.alpha[j]))
    if run.points[0] is None:
        return None, f"continuation at H = {model.H} from alpha = {backbone.alpha[j]:.4g}: {run.reason[0]}"
    return _collect(run, model, np.array([alpha]), problem, time.perf_counter() - t0,
                    backbone.pole_window), ""


def _same_unknown(base: CondensedHBM, model: CondensedHBM, k: int) -> int:
    """Index in ``model``'s unknowns of unknown ``k`` of ``base``, the same problem truncated at fewer
    harmonics: contact slots keep their index (slot-major layout), explicit modal coordinates shift
    by the extra contact slots."""
    if k < base.n_d:
        return k
    h = next(h for h, sl in enumerate(base.eta_slices) if sl.start <= k < sl.stop)
    return model.eta_slices[h].start + k - base.eta_slices[h].start


def _initial_guess(model: CondensedHBM, phi: np.ndarray, omega0: float, alpha0: float, xi0: float = 0.0,
                   reference: np.ndarray | None = None):
    """Linear mode ``φ`` (real, or complex with ``ξ₀``: :func:`_stuck_mode`) at amplitude ``α₀``, phase
    rotated so the phase unknown is real, its zero modes at the gauge reference ``reference`` (default 0)."""
    m1 = model.modal[1]
    hd = model.structure.harmonics[1]
    d1 = hd.B @ phi
    eta1 = m1.Phi.conj().T @ (hd.M @ phi)
    cand = np.r_[np.abs(d1), np.abs(eta1[model.S[1]])]
    k = int(np.argmax(cand))
    ref = d1[k] if k < model.p else eta1[model.S[1][k - model.p]]
    rot = alpha0 * np.exp(-1j * np.angle(ref))
    d = np.zeros((model.C, model.p))
    d[1], d[2] = (rot * d1).real, -(rot * d1).imag
    eta = [np.zeros(mh.w2.size, complex) for mh in model.modal]
    eta[1] = rot * eta1
    y = model.pack(d, eta)
    if model.zero_modes.size and reference is not None:
        y[model.eta_slices[0].start + model.zero_modes] = reference
    phase = (model.slot_index(1, True, k) if k < model.p
             else model.eta_index(1, k - model.p, True))
    return np.r_[y, omega0, xi0], phase


def _collect(run, model: CondensedHBM, alpha, problem: EPMCProblem, wall, window) -> Backbone:
    n = alpha.size
    nan = np.full(n, np.nan)
    omega, xi, drift = nan.copy(), nan.copy(), nan.copy()
    d = np.full((n, model.C, model.p), np.nan)
    lam = np.full_like(d, np.nan)
    eta = [np.full((n, mh.w2.size), np.nan, complex) for mh in model.modal]
    pinned = [np.zeros((model.zero_modes.size, 0))] * n
    iters = np.zeros(n, int)
    condition = nan.copy()
    status, reason = run.status.copy(), list(run.reason)
    for i, pt in enumerate(run.points):
        if pt is None:
            continue
        ev = pt.payload
        omega[i], xi[i], iters[i], condition[i] = pt.z[-2], pt.z[-1], pt.iterations, pt.condition
        d[i], lam[i], pinned[i] = ev.d, ev.lam, ev.gauge
        for h in range(model.H + 1):
            eta[h][i] = ev.eta[h]
        drift[i] = model.relative_drift(ev)
        if drift[i] > problem.drift_tol:
            status[i] = Status.DRIFT
            reason[i] = (f"mean force on a free body {drift[i]:.2e} (relative): no periodic "
                         "solution, the body ratchets")
    branch = np.array([(np.exp(p.s), p.z[-2], p.z[-1]) for p in run.branch]).reshape(-1, 3)
    return Backbone(alpha=alpha, omega=omega, xi=xi, zeta=xi / (2 * omega), status=status,
                    reason=reason, iterations=iters, d=d, lam=lam, eta=eta, pinned=pinned,
                    drift=drift, branch=branch, model=model, phase_index=problem.phase_index,
                    wall_time=wall, pole_window=tuple(window), drift_tol=problem.drift_tol,
                    amplitude=problem.amplitude, condition=condition)
