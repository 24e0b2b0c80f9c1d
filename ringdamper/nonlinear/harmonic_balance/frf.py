"""Nonlinear forced response: arc-length continuation in excitation frequency and resonance-peak
extraction (paper §2.6 Fig. 9, §3.4 Fig. 19g; docs/design.md §3.5).

The forcing is ``Re(γ F̂ e^{iωt})`` with ``F̂`` the structure's harmonic-1 forcing vector (phase 0),
structural damping the modal ratio ``zeta_s``. The curve starts from a converged fixed-frequency
solve at ``omega_start`` (seeded with the linearised stuck response) and follows the branch with
pseudo-arc-length steps until ω passes ``omega_end`` (status 1 if it turns back a whole band below
``omega_start`` instead). A rigid-body hold of the ring lost within a failed step is pinned and
the step retried, as in the EPMC (:meth:`ringdamper.nonlinear.harmonic_balance.forced.ForcedProblem.on_failure`). The
resonance peak is the maximum of the response measure along the branch, refined between the
neighbours of every sampled maximum near the largest (:func:`resonance_peak`) by a bounded Brent
search over the arc-length coordinate (each evaluation a converged solution on the hyperplane
normal to the local tangent, its corrector started from one factorisation of the bordered Jacobian
at the sampled maximum).

*Step control* (:data:`FORCED_STEPS`, docs/nonlinear_core.md §6). Near a resonance the response
vector runs once round a Nyquist circle: in the scaled arc-length metric its unit tangent turns by
about 2π across the peak, whatever the forcing. The arc length's rule "the tangent turns by about
``turn`` per step" therefore sets the point count (≈ 2π/turn + the corners of stick–slip
transitions). The forced curves use ``turn = 0.3`` rad (about 21 points round the circle, each
chord within ``turn/2`` of the arc) with steps up to 0.3 and a growth of 2 on easy steps; every
step still passes all the trusted-step tests of :mod:`ringdamper.nonlinear.solvers.continuation`, and the
peak comes from the refinement, not from the spacing of the points. The tangents, solved by GMRES
on the corrector's last LU, are accurate to 1e-4 (scaled 2-norm; the continuation's default is 1e-6):
they only set the predictor, the corrector's hyperplane and the geometry tests, which work at
0.3–0.6 rad, and a refined peak moves by at most 1e-6 relative with them (measured on Table 3's eight
curves: 9 % less CPU, the slowest 16.2 → 13.5 s). Every point's local stability
comes from Hill's method on the full modal harmonic-balance Jacobian
(:mod:`ringdamper.nonlinear.harmonic_balance.stability`).
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field, replace

import numpy as np
from scipy.optimize import minimize_scalar

from ringdamper.nonlinear.contact.elements import Elements
from ringdamper.nonlinear.contact.friction import FrictionContacts
from ringdamper.nonlinear.fourier import default_nt
from ringdamper.nonlinear.harmonic_balance.condensed import CondensedHBM, pole_modes, structural_damping
from ringdamper.nonlinear.harmonic_balance.forced import ForcedProblem
from ringdamper.nonlinear.harmonic_balance.response import response_harmonics, time_peak
from ringdamper.nonlinear.harmonic_balance.stability import hill_exponents, is_stable, modal_hill_matrices
from ringdamper.nonlinear.harmonic_balance.structure import Structure
from ringdamper.nonlinear.solvers.continuation import StepControl, arclength
from ringdamper.nonlinear.solvers.jacobian import bordered, dense
from ringdamper.nonlinear.solvers.newton import Factorization, newton
from ringdamper.status import Status

#: Step control of the forced responses (module docstring): arc length in the scaled metric of
#: :func:`forced_response`, nominal tangent turn 0.3 rad per step, tangents to 1e-4.
FORCED_STEPS = StepControl(initial=0.05, minimum=1e-6, maximum=0.3, grow=2.0, turn=0.3,
                           tangent_rtol=1e-4)


@dataclass
class FRF:
    """Forced-response branch: per point ``omega`` [rad/s], ``q_h1`` (first-harmonic magnitude
    of the response DoF), ``q_peak`` (peak of its time signal) [m] and ``drift`` (relative mean
    force on a gauged free body, see :mod:`ringdamper.nonlinear.harmonic_balance.condensed`), ``growth`` (largest
    real part of the point's Floquet exponents [1/s]) and ``stable`` (Hill's method; both None when
    not computed); ``status`` 0 when the branch reached ``omega_end`` (DRIFT if a point's drift
    exceeds ``drift_tol``); ``points``/``tangents``/``scales`` of the continuation."""

    gamma: float
    zeta_s: float
    omega: np.ndarray
    q_h1: np.ndarray
    q_peak: np.ndarray
    drift: np.ndarray
    status: int
    reason: str
    points: list = field(repr=False)
    tangents: list = field(repr=False)
    scales: list = field(repr=False)
    problem: ForcedProblem = field(repr=False)
    tol: float = 1e-10
    max_iter: int = 20
    wall_time: float = 0.0
    growth: np.ndarray | None = None
    stable: np.ndarray | None = None

    def harmonics(self, j: int) -> list:
        """Harmonics ``Q_h = Φ_h η_h`` (complex, ``h = 0..H``) of every DoF at branch point ``j``."""
        model = self.problem.model
        return [m.Phi @ e for m, e in zip(model.modal, self.points[j].payload.eta)]


@dataclass
class Peak:
    """Resonance peak: ``omega`` [rad/s], ``q_h1``, ``q_peak`` [m], ``index`` of the nearest
    branch point, ``refined`` (False if the maximum sits at an end of the branch or the
    refinement failed), and the converged state ``z``."""

    omega: float
    q_h1: float
    q_peak: float
    index: int
    refined: bool
    z: np.ndarray = field(repr=False)


def forced_response(structure: Structure, contacts: FrictionContacts | Elements, gamma: float,
                    omega_start: float, omega_end: float, *, H: int = 1, nt: int | None = None,
                    zeta_s: float = 0.0, pole_band: float = 0.05, tol: float = 1e-8,
                    max_iter: int = 20, steps: StepControl | None = None,
                    max_points: int = 1000, drift_tol: float = 1e-8,
                    stability: bool = True) -> FRF:
    """Forced response at forcing amplitude ``gamma`` [N] from ``omega_start`` to ``omega_end``.

    ``steps`` controls the arc length measured on unknowns scaled by their running maxima (times
    √n) and ω by ``|omega_end − omega_start|`` (default :data:`FORCED_STEPS`). ``pole_band``
    keeps modes with ``ω_r ∈ h·[ω_lo(1−pole_band), ω_hi(1+pole_band)]`` explicit. ``stability``:
    classify every point by Hill's method (:func:`point_stability`).
    """
    t0 = time.perf_counter()
    nt = default_nt(H) if nt is None else nt
    steps = steps or FORCED_STEPS
    lo, hi = sorted((omega_start, omega_end))
    explicit = pole_modes(structure, H, lo * (1 - pole_band), hi * (1 + pole_band)) \
        if pole_band > 0 else None
    contacts = contacts.for_pairs(structure.npairs)
    damping = structural_damping(structure, H, zeta_s)
    model = CondensedHBM(structure, contacts, H, nt, explicit=explicit, damping=damping,
                         forced=True, gamma=gamma, expansion=(omega_start, 0.0))   # the first Newton's start
    problem = ForcedProblem(model)
    y0 = problem.linear_guess(omega_start, contacts.stuck_stiffness().ravel())
    res = newton(problem.at_frequency(omega_start), y0, model.core_scale, tol, max_iter)
    if not res.converged:
        return _frf(gamma, zeta_s, [], [], [], Status.NO_CONVERGENCE,
                    f"start point: {res.reason}", problem, tol, max_iter, drift_tol, t0)
    z0 = np.r_[res.z, omega_start]
    problem.accept(z0, res.payload)
    branch = ForcedBranch(problem, omega_start, omega_end)
    direction = np.zeros(z0.size)
    direction[-1] = branch.sign
    run = arclength(branch, z0, direction, branch.rescale(z0, np.zeros(z0.size)),
                    replace(steps, tol=tol, max_iter=max_iter, max_points=max_points))
    status, reason = run.status, run.reason
    if status == Status.CONVERGED and branch.sign * (run.points[-1].z[-1] - omega_end) < 0:
        status, reason = Status.NO_CONVERGENCE, "the branch turned back below omega_start"
    frf = _frf(gamma, zeta_s, run.points, run.tangents, run.scales, status, reason,
               problem, tol, max_iter, drift_tol, t0)
    if stability:
        frf.growth, frf.stable = point_stability(frf)
        frf.wall_time = time.perf_counter() - t0
    return frf


class ForcedBranch:
    """The forced-response branch from ``omega_start`` towards ``omega_end`` as a
    :class:`ringdamper.nonlinear.solvers.continuation.CurveProblem` of the solve ``problem``: its residual and
    history hooks, the arc-length scaling (:meth:`rescale`) and the end of the band (:meth:`stop`)."""

    jump_mask = None

    def __init__(self, problem: ForcedProblem, omega_start: float, omega_end: float):
        self.problem, self.omega_start, self.omega_end = problem, omega_start, omega_end
        self.fun, self.accept, self.on_failure = problem.fun, problem.accept, problem.on_failure
        self.span = abs(omega_end - omega_start)
        self.sign = np.sign(omega_end - omega_start)
        self.root_n = np.sqrt(problem.model.n_core)

    def rescale(self, z, scale):
        """Running maxima of the unknowns, the response part weighted by ``1/√n`` so that the arc
        length measures the RMS relative change of the response and the relative change of ω
        alike (otherwise hundreds of contact unknowns would dominate the step)."""
        return np.maximum(scale, np.r_[self.root_n * self.problem.model.core_scale(z[:-1]), self.span])

    def stop(self, z) -> bool:
        """Past ``omega_end``, or turned back (after a fold) a whole band before ``omega_start``."""
        return (self.sign * (z[-1] - self.omega_end) >= 0
                or self.sign * (self.omega_start - z[-1]) >= self.span)


def point_stability(frf: FRF, tol: float = 1e-6) -> tuple[np.ndarray, np.ndarray]:
    """Largest real part of the Floquet exponents [1/s] of every branch point and its stability
    (``Re λ ≤ tol·ω``), by Hill's method on the full modal Jacobian
    (:func:`ringdamper.nonlinear.harmonic_balance.stability.modal_hill_matrices`), each at its accepted point's gauged
    directions (the evaluations leave the solve's gauge state as it was)."""
    model, gauge = frf.problem.model, frf.problem.gauge
    growth = np.empty(len(frf.points))
    stable = np.empty(len(frf.points), bool)
    for i, p in enumerate(frf.points):
        omega = p.z[-1]
        ev = replace(model.evaluate(p.z[:-1], omega, 0.0, gauge, True), gauge=p.payload.gauge)
        J, D1 = modal_hill_matrices(model, ev, omega)
        lam = hill_exponents(J, D1, omega)
        growth[i], stable[i] = np.max(lam.real), is_stable(lam, omega, tol)
    return growth, stable


def _frf(gamma, zeta_s, points, tangents, scales, status, reason, problem, tol, max_iter,
         drift_tol, t0):
    model = problem.model
    omega = np.array([p.z[-1] for p in points])
    h1, peak = np.array([_measures(model, p.payload) for p in points]).reshape(-1, 2).T
    drift = np.array([model.relative_drift(p.payload) for p in points])
    if status == Status.CONVERGED and np.any(drift > drift_tol):
        status = Status.DRIFT
        reason = (f"mean force on a free body up to {drift.max():.2e} (relative): no periodic "
                  "response there, the body ratchets")
    return FRF(gamma=gamma, zeta_s=zeta_s, omega=omega, q_h1=h1, q_peak=peak, drift=drift,
               status=int(status), reason=reason, points=points, tangents=tangents, scales=scales,
               problem=problem, tol=tol, max_iter=max_iter, wall_time=time.perf_counter() - t0)


def _measures(model: CondensedHBM, ev) -> tuple[float, float]:
    q = response_harmonics(model.modal, ev.eta)
    return abs(q[1]), time_peak(q)


#: Local maxima of the sampled measure refined by :func:`resonance_peak`: those within this
#: fraction of the largest sampled value (a narrow resonance between two coarse points can top a
#: sampled maximum that is not the largest).
PEAK_CANDIDATES = 0.05


def resonance_peak(frf: FRF, measure: str = "peak", rtol: float = 1e-4) -> Peak:
    """Maximum of ``measure`` (``"peak"``: time-signal peak; ``"h1"``: first-harmonic magnitude)
    along the branch. Every interior local maximum of the sampled measure within
    :data:`PEAK_CANDIDATES` of the largest is refined between its neighbours to ``rtol`` times
    their distance in arc length (the measure is quadratic at its maximum, so its relative error
    is of order ``rtol²``); the largest refined value wins (the largest sampled point, unrefined,
    if no refinement beats it)."""
    if measure not in ("peak", "h1"):
        raise ValueError("measure must be 'peak' or 'h1'")
    if not frf.points:
        raise ValueError("empty forced response")
    k = 1 if measure == "peak" else 0
    values = frf.q_peak if k else frf.q_h1
    i = int(np.argmax(values))
    best = Peak(frf.omega[i], frf.q_h1[i], frf.q_peak[i], i, False, frf.points[i].z)
    inner = np.arange(1, len(values) - 1)
    local = inner[(values[inner] >= values[inner - 1]) & (values[inner] >= values[inner + 1])
                  & (values[inner] >= (1 - PEAK_CANDIDATES) * values[i])]
    for j in local[np.argsort(-values[local])]:
        refined = _refine_peak(frf, int(j), k, rtol)
        if refined is not None and (refined.q_peak if k else refined.q_h1) >= \
                (best.q_peak if k else best.q_h1):
            best = refined
    return best


def _refine_peak(frf: FRF, i: int, k: int, rtol: float) -> Peak | None:
    """Maximum of measure ``k`` (0: first harmonic, 1: time-signal peak) between the neighbours of
    the interior point ``i``: bounded Brent search over the arc-length coordinate σ on the
    hyperplane normal to the tangent at ``i`` (each evaluation a converged solution, its corrector
    started from one factorisation of the bordered Jacobian at ``i``). None if the neighbours do
    not straddle the hyperplane or the solve fails."""
    model, problem = frf.problem.model, frf.problem
    problem.accept(frf.points[i].z, frf.points[i].payload)      # gauge state of point i
    scale, t = frf.scales[i], frf.tangents[i]
    zi = frf.points[i].z
    plane = t / scale
    sig = [plane @ (frf.points[j].z - zi) for j in (i - 1, i + 1)]
    if not sig[0] < 0 < sig[1]:
        return None
    cache = {}
    ev = problem.fun(zi, True)
    start = Factorization(dense(bordered(ev.J, rows=plane)), ev.trivial, ev.n_core, overwrite=True)   # chord start

    def solve(sigma):
        j = i - 1 if sigma < 0 else i + 1
        w = sigma / sig[0 if sigma < 0 else 1]
        guess = zi + w * (frf.points[j].z - zi)

        def on_plane(z, jac):
            return problem.fun(z, jac).extended(plane @ (z - zi) - sigma, rows=plane)

        res = newton(on_plane, guess, lambda _: scale, frf.tol, frf.max_iter, factorization=start)
        cache[sigma] = res
        return res

    def objective(sigma):
        res = solve(sigma)
        return -_measures(model, res.payload)[k] if res.converged else 0.0

    opt = minimize_scalar(objective, bounds=(sig[0], sig[1]), method="bounded",
                          options={"xatol": rtol * (sig[1] - sig[0])})
    res = cache.get(opt.x) or solve(opt.x)
    if not res.converged:
        return None
    h1, pk = _measures(model, res.payload)
    return Peak(res.z[-1], h1, pk, i, True, res.z)
