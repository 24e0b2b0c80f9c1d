"""Predictor–corrector continuation: natural parameter (log α for the dNNM), pseudo-arc-length
(excitation frequency for the forced response) and their combination (natural, then arc length
past a fold in the parameter, :func:`natural_then_arclength`), after Allgower & Georg,
*Introduction to Numerical Continuation Methods* (2003), ch. 6 (step-length adaptation).

Common rules. Tangent predictor, Newton corrector reusing the last factorisation while it
contracts (:func:`ringdamper.nonlinear.newton.newton`). Every accepted point gets a fresh
Jacobian and its own unit tangent ``t``, measured in a scaled metric ``u`` (unknowns over their
scales, see each driver). A corrected point ``u₁`` reached from the trusted point ``u₀`` (tangent
``t₀``) is *trusted* only if the geometry of the step fits one smooth branch
(:func:`_step_geometry`, :func:`_untrusted`):

* **turn** ``θ = ∠(t₀, t₁)`` at most ``max_angle`` (curvature test, default twice the nominal
  turn :attr:`StepControl.turn`);
* **distance from the predictor**: the chord ``c = u₁ − u₀`` makes the angle ``φ₀ = ∠(c, t₀)``
  with the predictor direction (``tan φ₀`` = distance of the corrector from the predictor / step
  for the arc-length corrector), at most ``max_angle``;
* **chord–tangent consistency**: on one smooth (or cornered) branch ``φ₀ + φ₁ ≈ θ`` (``φ₁ =
  ∠(c, t₁)``; equality for a plane arc or a corner), whereas a corrector that lands on another
  branch gives ``φ₀ + φ₁ ≫ θ`` (a parallel branch: ``θ ≈ 0``, ``φ₀ = φ₁ = atan(distance/step)``);
  rejected when ``φ₀ + φ₁ − θ > max_angle / 2``, at every step size.

A rejected step (no convergence, or untrusted) is halved from the last trusted point (bisection)
until it is trusted or falls below :attr:`StepControl.minimum`, where the run stops with a
status. The turn test is waived once the step is below ``corner × minimum`` (the branches of
Jenkins elements are piecewise smooth: the tangent turns by a finite angle at a stick–slip
transition, whatever the step), the consistency test never. After an accepted step the step is
multiplied by ``min(grow, turn/θ)`` when the corrector was cheap (effort ≤ ``easy``, see
:func:`newton`), by ``min(1, turn/θ)`` otherwise and halved when it was hard (effort ≥
``hard``), never below half (so the tangent turns by about ``turn`` per step, whatever the
initial and maximum steps). A corrector is a failure once it has used
:attr:`StepControl.corrector` fresh Jacobians without converging (fail fast: a smaller step is
cheaper than a long Newton far from the branch), and so is one whose damped Newton step needs a
damping ``λ ≤`` :attr:`StepControl.give_up_damping` (its predictor lies outside the corrector's
region of contraction, see :func:`ringdamper.nonlinear.newton.newton`). ``jump_mask`` restricts
the geometry to the unknowns that identify the branch (the EPMC leaves out the mean values, which
move freely where the last contact holding a rigid-body motion lets go). Failures never raise:
they end the run with a status (:class:`ringdamper.status.Status`). A natural step that ends
between two grid values may stop its corrector earlier (:attr:`StepControl.between`): such a point
carries only the predictor and the next step's geometry; every grid value is solved to the run's
tolerance.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable

import numpy as np

from ringdamper.nonlinear import krylov
from ringdamper.nonlinear.jacobian import bordered, dense, is_operator
from ringdamper.nonlinear.newton import Factorization, NewtonResult, linear_solver, newton
from ringdamper.status import Status

# Weight, in the arc length of :func:`natural_then_arclength`, of the unknowns outside ``jump_mask``
# (relative to the others): the mean values of a body that moves freely where its last holding
# contact lets go. At full weight its drift dominates the tangent there, the steps walk along the
# drift and the geometry tests, which look at the other unknowns, see noise.
FREE_WEIGHT = 0.3

#: damping λ of a corrector's Newton step at or below which the corrector fails and its step is
#: halved (:attr:`StepControl.give_up_damping`): on the hard rings of the campaigns 1/16 cuts the fresh
#: Jacobians by a third, 1/8 and 1/4 lose top points and 1/64 saves less
#: (docs/nonlinear_core.md §4.1)
GIVE_UP_DAMPING = 1.0 / 16

#: largest angle [rad] by which the corrector's error at a point between grid values may tilt the
#: chord of its step (:meth:`StepControl.corrector_tolerance`)
BETWEEN_PER_STEP = 1e-3


@dataclass
class StepControl:
    """Step-size rules (in the continuation parameter or arc length). ``turn`` [rad]: nominal
    angle between the tangents of successive points (the step follows the curvature); a step
    whose tangent turns by more than twice that is rejected and halved (module docstring).
    ``between``: looser corrector tolerance of the natural steps that end between grid values
    (:meth:`corrector_tolerance`; None: the run's tolerance everywhere). ``give_up_damping``: a
    corrector whose damped Newton step needs ``λ`` at or below it fails its step at once (module
    docstring; None: only :attr:`corrector` ends it). ``quasi_newton``: the correctors take good
    Broyden steps on their factorisation instead of chord steps
    (:func:`ringdamper.nonlinear.newton.newton`).
    ``tangent_rtol``: accuracy (scaled 2-norm) of the arc-length tangents that GMRES solves on a
    lagged LU (:mod:`ringdamper.nonlinear.krylov`)."""

    initial: float
    minimum: float
    maximum: float
    grow: float = 1.5
    easy: float = 1.5        # corrector effort (:attr:`NewtonResult.effort`) below which ds grows
    hard: float = 4.0        # effort above which ds shrinks
    turn: float = 0.1
    corrector: int | None = None  # fresh Jacobians of a corrector before its step is rejected (None: max_iter)
    between: float | None = None  # corrector tolerance between grid values (None: the run's tol)
    give_up_damping: float | None = GIVE_UP_DAMPING  # a corrector that needs damping this deep fails its step
    tangent_rtol: float = krylov.RTOL  # accuracy of arc-length tangents by GMRES on a lagged LU
    quasi_newton: bool = False  # correctors take quasi-Newton steps on their factorisation

    def __post_init__(self):
        if not 0 < self.minimum <= self.initial:
            raise ValueError(f"StepControl: need 0 < minimum <= initial, got minimum="
                             f"{self.minimum}, initial={self.initial}")
        if self.maximum < self.minimum:
            raise ValueError(f"StepControl: maximum={self.maximum} is below minimum="
                             f"{self.minimum}")
        if not 0 < self.turn < np.pi / 4:
            raise ValueError(f"StepControl: turn must lie in (0, pi/4) rad, got {self.turn}")
        if self.give_up_damping is not None and not 0 < self.give_up_damping < 1:
            raise ValueError(f"StepControl: give_up_damping must lie in (0, 1) or be None, got "
                             f"{self.give_up_damping}")
        if self.corrector is not None and self.corrector < 1:
            raise ValueError(f"StepControl: corrector must be >= 1 fresh Jacobians, got {self.corrector}")

    def corrector_tolerance(self, tol: float, ds: float, on_grid: bool) -> float:
        """Newton tolerance of a natural step of size ``ds``: ``tol`` on a grid value; between grid
        values, where a point only carries the predictor and the step's geometry, up to
        :attr:`between`, and at most ``BETWEEN_PER_STEP·ds`` so that the corrector's error tilts
        the chord by no more than that angle [rad] (``|δu| ≤ tol``, chord ``≥ ds``; the geometry
        tests work at 0.1–0.2 rad)."""
        if on_grid or self.between is None:
            return tol
        return max(tol, min(self.between, BETWEEN_PER_STEP * ds))

    def corrector_iterations(self, max_iter: int) -> int:
        """Fresh Jacobians a predictor–corrector step may use: :attr:`corrector`, at most ``max_iter``."""
        return max_iter if self.corrector is None else min(self.corrector, max_iter)

    def adapt(self, ds: float, res, turn: float = 0.0) -> float:
        """New step from the corrector's effort (Jacobians + iterations / chord budget, see
        :func:`ringdamper.nonlinear.newton.newton`: cheap chord iterations count little) and the
        tangent turn ``turn`` [rad] of the accepted step."""
        factor = self.grow if res.effort <= self.easy else 1.0
        if res.effort >= self.hard:
            factor = 0.5
        if turn > 0:
            factor = min(factor, self.turn / turn)
        return min(ds * max(factor, 0.5), self.maximum)


@dataclass
class ContinuationPoint:
    """An accepted point: parameter ``s``, unknowns ``z``, the problem's evaluation there
    (``payload``), Newton iterations, and ``condition``, the κ₁ estimate of its equilibrated
    Jacobian where :func:`natural` factorised it exactly (a grid value; NaN elsewhere)."""

    s: float
    z: np.ndarray
    payload: Any
    iterations: int
    condition: float = np.nan


@dataclass
class NaturalResult:
    """Solutions at the requested parameter values (``None`` where not converged), their
    statuses and reasons, and every accepted point of the branch."""

    grid: np.ndarray
    points: list
    status: np.ndarray
    reason: list
    branch: list = field(default_factory=list)


def _angle(a: np.ndarray, b: np.ndarray) -> float:
    """Angle [rad] between two vectors (π/2 if one vanishes)."""
    na, nb = np.linalg.norm(a), np.linalg.norm(b)
    if na == 0 or nb == 0:
        return np.pi / 2
    return float(np.arccos(np.clip(a @ b / (na * nb), -1.0, 1.0)))


def _step_geometry(t0, t1, chord, mask=None):
    """Turn ``θ = ∠(t₀, t₁)`` and the chord's angles ``φ₀ = ∠(c, t₀)``, ``φ₁ = ∠(c, t₁)`` of a
    step, over the unknowns ``mask`` (default all)."""
    keep = slice(None) if mask is None else mask
    t0, t1, chord = t0[keep], t1[keep], chord[keep]
    return _angle(t0, t1), _angle(chord, t0), _angle(chord, t1)


def _untrusted(geometry, max_angle: float, corner: bool) -> str:
    """Why the step of ``geometry`` (:func:`_step_geometry`) is not trusted ("" if it is);
    ``corner``: the step is small enough for the turn test to be waived."""
    turn, ahead, behind = geometry
    if ahead + behind - turn > 0.5 * max_angle:
        return (f"corrector jumped (possible branch switch): chord at {ahead:.3g} and "
                f"{behind:.3g} rad from the end tangents, which turn by {turn:.3g} rad")
    if corner:
        return ""
    if ahead > max_angle:
        return f"corrector far from the predictor ({ahead:.3g} rad off the tangent)"
    if turn > max_angle:
        return f"tangent turned by {turn:.3g} rad"
    return ""


def _unit(v):
    return v / np.linalg.norm(v)


def natural(fun: Callable, dfun_ds: Callable, z0: np.ndarray, grid: np.ndarray,
            scale: Callable, steps: StepControl, tol: float, max_iter: int,
            accept: Callable | None = None, s_start: float | None = None,
            on_failure: Callable[[], bool] | None = None,
            jump_mask: np.ndarray | None = None, max_angle: float | None = None,
            corner: float = 100.0) -> NaturalResult:
    """Continuation in the scalar parameter ``s`` from ``s_start`` (default ``grid[0]``; ``z0``
    is the guess there) over the increasing ``grid``, landing exactly on every grid value (so grid
    outputs are converged solutions, not interpolants).

    Tangents: at a grid value from the LU of its Jacobian, equilibrated, whose condition estimate the
    point keeps (:attr:`ContinuationPoint.condition`); between grid values by GMRES on the corrector's
    last LU (:func:`ringdamper.nonlinear.newton.linear_solver`). Either way the next corrector starts
    from the corrector's own chain of LUs, not from the grid value's exact one: handed on, that LU
    made correctors cheaper, the step control then grew the steps into the stretch where pairs lift
    off, and one ring of twenty (t036 of the paper design) took twice as long and lost its top point
    (docs/nonlinear_core.md §4.6).

    ``fun(z, s, jacobian) -> (r, J, trivial, n_core, payload)``; ``dfun_ds(z, s)`` is ``∂r/∂s``;
    ``accept(z, payload)`` is called on every accepted point (e.g. to update a gauge);
    ``on_failure()`` after a failed corrector: if it returns True the problem has changed (e.g. a
    rigid-body direction was pinned) and the same step is tried again before it is halved.
    The step geometry (module docstring) is measured on ``u = [z/(√n·scale(z₀)), s]`` with the
    tangent ``(dz/ds, 1)`` of every accepted point; in addition a step is rejected when the
    tangent oriented along the chord points to decreasing ``s`` (a fold in ``s`` between the two
    points, which natural continuation cannot pass). ``jump_mask``: unknowns the geometry looks
    at (default all); ``max_angle`` (default ``2·steps.turn``) and ``corner`` as in
    :func:`arclength`.
    """
    grid = np.asarray(grid, float)
    n = grid.size
    points, status = [None] * n, np.full(n, Status.NOT_REACHED, int)
    reason = ["not reached"] * n
    out = NaturalResult(grid, points, status, reason)
    s = grid[0] if s_start is None else min(s_start, grid[0])
    res = newton(lambda z, jac: fun(z, s, jac), z0, scale, tol, max_iter)
    if not res.converged:
        status[0], reason[0] = Status.NO_CONVERGENCE, f"start point: {res.reason}"
        return out
    max_angle = 2 * steps.turn if max_angle is None else max_angle
    mask = None if jump_mask is None else np.r_[jump_mask, True]
    root_n = np.sqrt(z0.size)
    z = res.z
    on_grid = s == grid[0]
    fac_t, tangent = _natural_tangent(fun, dfun_ds, z, s, res.factorization, scale, exact=on_grid)
    fac = res.factorization if on_grid else fac_t
    out.branch.append(ContinuationPoint(s, z, res.payload, res.iterations))
    gi = 0
    if on_grid:
        _record(out, 0, s, res, accept, fac_t)
        gi = 1
    elif accept is not None:
        accept(z, res.payload)
    ds = steps.initial
    corrector = steps.corrector_iterations(max_iter)
    while gi < n:
        s_t = min(s + ds, grid[gi])
        on_grid = s_t >= grid[gi] - 1e-12 * max(1.0, abs(grid[gi]))
        s_t = grid[gi] if on_grid else s_t
        z_pred = z + (s_t - s) * tangent
        res = newton(lambda zz, jac: fun(zz, s_t, jac), z_pred, scale,
                     steps.corrector_tolerance(tol, s_t - s, on_grid), corrector, factorization=fac,
                     give_up_damping=steps.give_up_damping, quasi_newton=steps.quasi_newton)
        why = res.reason
        if res.converged:
            fac_t, tangent_t = _natural_tangent(fun, dfun_ds, res.z, s_t, res.factorization, scale,
                                                exact=on_grid)
            geometry, fold = _natural_geometry(z, s, tangent, res.z, s_t, tangent_t,
                                               root_n * scale(z), mask)
            why = ("fold in s between the points" if fold else
                   _untrusted(geometry, max_angle, s_t - s <= corner * steps.minimum))
        if not why:
            s, z, tangent = s_t, res.z, tangent_t
            fac = res.factorization if on_grid else fac_t
            out.branch.append(ContinuationPoint(s, z, res.payload, res.iterations))
            if on_grid:
                _record(out, gi, s, res, accept, fac_t)
                gi += 1
            elif accept is not None:
                accept(z, res.payload)
            ds = steps.adapt(ds, res, geometry[0])
            continue
        if on_failure is not None and on_failure():
            continue
        ds = 0.5 * (s_t - s)
        if ds < steps.minimum:
            _stopped(out, range(gi, n), f"step below minimum at s={s:.6g}: {why}",
                     f"continuation stopped at s={s:.6g}")
            break
    return out


def _natural_geometry(z0, s0, tangent0, z1, s1, tangent1, w, mask):
    """Geometry (:func:`_step_geometry`) of the natural step from ``(z0, s0)`` to ``(z1, s1)``
    in ``u = [z/w, s]`` with the tangents ``(dz/ds, 1)`` at both ends, and whether the end
    tangent oriented along the chord points to decreasing ``s`` (a fold in ``s`` between them)."""
    chord = np.append((z1 - z0) / w, s1 - s0)
    t0, t1 = _unit(np.append(tangent0 / w, 1.0)), _unit(np.append(tangent1 / w, 1.0))
    if t1 @ chord < 0:
        t1 = -t1
    return _step_geometry(t0, t1, chord, mask), t1[-1] <= 0


def _natural_tangent(fun, dfun_ds, z, s, previous, scale, exact=False):
    """Solver of the Jacobian at ``(z, s)`` and the tangent ``dz/ds = −J⁻¹ ∂r/∂s``. The solver is
    :func:`ringdamper.nonlinear.newton.linear_solver` on the factorisation of the solver ``previous``
    or, with ``exact``, the LU of the Jacobian itself, equilibrated by the scales ``scale(z)``, which
    gives the point its condition estimate (:meth:`ringdamper.nonlinear.newton.Factorization.condition`)."""
    _, J, trivial, n_core, _ = fun(z, s, True)
    if exact:
        fac = Factorization(dense(J), trivial, n_core, overwrite=is_operator(J), scale=scale(z))
    else:
        fac = linear_solver(J, trivial, n_core, previous, 1.0 / scale(z))
    return fac, fac.solve(-dfun_ds(z, s))


def _record(out: NaturalResult, i: int, s: float, res: NewtonResult, accept, fac=None):
    """Grid value ``i`` solved: ``res`` at ``s``, with the condition estimate of ``fac``, the exact
    factorisation of its Jacobian (:func:`_natural_tangent`), if given."""
    condition = np.nan if fac is None else fac.condition()
    out.points[i] = ContinuationPoint(s, res.z, res.payload, res.iterations, condition)
    out.status[i], out.reason[i] = Status.CONVERGED, ""
    if accept is not None:
        accept(res.z, res.payload)


def _stopped(out: NaturalResult, indices, why: str, after: str):
    """Statuses of the grid values ``indices`` left unsolved where a run stopped: no convergence
    (reason ``why``) at the first, not reached (reason ``after``) at the others."""
    for k in indices:
        first = k == indices[0]
        out.status[k] = Status.NO_CONVERGENCE if first else Status.NOT_REACHED
        out.reason[k] = why if first else after


@dataclass
class ArclengthResult:
    points: list
    tangents: list
    scales: list
    status: int
    reason: str


def arclength(fun: Callable, z0: np.ndarray, direction: np.ndarray, scale: np.ndarray,
              steps: StepControl, tol: float, max_iter: int, stop: Callable[[np.ndarray], bool],
              max_points: int, max_angle: float | None = None, corner: float = 100.0,
              rescale: Callable | None = None, accept: Callable | None = None,
              on_failure: Callable[[], bool] | None = None,
              jump_mask: np.ndarray | None = None) -> ArclengthResult:
    """Pseudo-arc-length continuation of ``r(z) = 0`` (one fewer equation than unknowns).

    ``fun(z, jacobian) -> (r, J, trivial, n_core, payload)``, ``J`` of shape ``(n−1, n)``; ``z0`` a
    solution; ``direction`` the initial orientation; ``scale`` the variable scaling (arc length is
    measured on ``u = z / scale``; the corrector stays on the hyperplane through the predictor
    normal to the tangent). Every accepted point gets its tangent from a fresh Jacobian (the null
    vector of ``J``, oriented along the chord of the step). A step is trusted by the geometry
    tests of the module docstring (``max_angle``, default ``2·steps.turn``; the turn test is
    waived below ``corner × steps.minimum``, the chord–tangent consistency test never) and
    otherwise halved from the last trusted point. Stops with status 0 when ``stop(z)`` is true.
    ``rescale(z, scale) -> scale`` may update the scaling after every accepted point (the tangent
    is carried over in unscaled form); ``accept(z, payload)`` is called on the start and every
    accepted point (history updates). ``tangents`` and ``scales`` in the result hold the unit
    tangent (in ``u``) and the scaling in force at every point. ``on_failure()`` and
    ``jump_mask`` as in :func:`natural`.
    """
    max_angle = 2 * steps.turn if max_angle is None else max_angle
    r0, J0, trivial0, n_core0, payload0 = fun(z0, True)
    if accept is not None:
        accept(z0, payload0)
    last_fac, t = _tangent(J0, trivial0, n_core0, direction / scale, scale, None)
    pts, tans, scales = [ContinuationPoint(0.0, z0, payload0, 0)], [t], [scale]
    z, s, ds = z0, 0.0, steps.initial
    corrector = steps.corrector_iterations(max_iter)

    def step(d, ds, fac):
        """Corrector from ``z + ds·d`` on the hyperplane normal to ``d`` (scaled), and the tests
        against the trusted tangent ``t``: ``(result, tangent, factorisation, turn, why)``."""
        zp, plane = z + ds * d * scale, d / scale

        def on_plane(zz, jac):
            r, J, trivial, n_core, payload = fun(zz, jac)
            Jb = bordered(J, rows=plane) if jac else None
            return np.append(r, plane @ (zz - zp)), Jb, trivial, n_core, payload

        res = newton(on_plane, zp, lambda _: scale, tol, corrector, factorization=fac,
                     give_up_damping=steps.give_up_damping, quasi_newton=steps.quasi_newton)
        if not res.converged:
            return res, None, None, 0.0, res.reason
        chord = (res.z - z) / scale
        _, J1, trivial1, n_core1, _ = fun(res.z, True)
        fac1, t1 = _tangent(J1, trivial1, n_core1, chord, scale, res.factorization, steps.tangent_rtol)
        geometry = _step_geometry(t, t1, chord, jump_mask)
        why = _untrusted(geometry, max_angle, ds <= corner * steps.minimum)
        if not why and _angle(-t, chord) <= np.pi / 4:
            why = "corrector went back along the branch"
        return res, t1, fac1, geometry[0], why

    while len(pts) < max_points:
        res, t1, fac1, turn, why = step(t, ds, last_fac)
        if why and ds <= corner * steps.minimum:
            turned = _turn_corner(step, fun, z, t, ds, corner * steps.minimum, scale)
            if turned:
                ds, (res, t1, fac1, turn, why) = turned
        if not why:
            z, t, s, last_fac = res.z, t1, s + ds, fac1
            pts.append(ContinuationPoint(s, z, res.payload, res.iterations))
            tans.append(t)
            scales.append(scale)
            if accept is not None:
                accept(z, res.payload)
            if stop(z):
                return ArclengthResult(pts, tans, scales, Status.CONVERGED, "")
            if rescale is not None:
                new = rescale(z, scale)
                t, scale = _unit(t * scale / new), new
            ds = steps.adapt(ds, res, turn)
            continue
        if on_failure is not None and on_failure():
            continue
        ds *= 0.5
        if ds < steps.minimum:
            return ArclengthResult(pts, tans, scales, Status.NO_CONVERGENCE,
                                   f"step below minimum: {why}")
    return ArclengthResult(pts, tans, scales, Status.MAX_POINTS, f"{max_points} points reached")


def _turn_corner(step, fun, z, t, ds, largest, scale):
    """Past a corner of a piecewise-smooth branch where it turns back (by more than 90°), the
    hyperplane normal to the incoming tangent ``t`` misses the outgoing branch. Its direction is
    the null vector of the Jacobian just past the corner (at the predictor ``z + ds·t``); both
    orientations are tried as predictor directions with steps ``ds``, ``4·ds``, … up to
    ``largest``; each must pass :func:`arclength`'s tests (and not lead back along the incoming
    branch). Returns ``step``'s tuple, or None."""
    _, J, trivial, n_core, _ = fun(z + ds * t * scale, True)
    fac, ahead = _tangent(J, trivial, n_core, t, scale, None)
    sizes = [ds * 4.0 ** k for k in range(int(np.log(largest / ds) / np.log(4.0)) + 1)]
    for size in sizes:
        for d in (ahead, -ahead):
            trial = step(d, size, fac)
            if not trial[-1]:
                return size, trial
    return None


def _tangent(J, trivial, n_core, direction_u, scale, previous, rtol=krylov.RTOL):
    """Solver of ``J`` bordered by ``direction_u / scale`` (:func:`ringdamper.nonlinear.newton.linear_solver`,
    on the factorisation of the solver ``previous``, if any, to ``rtol``) and the unit tangent in scaled
    variables: ``J (scale·t) = 0``, oriented along ``direction_u``."""
    e = np.zeros(J.shape[1])
    e[-1] = 1.0
    fac = linear_solver(bordered(J, rows=direction_u / scale), trivial, n_core, previous, 1.0 / scale,
                        rtol)
    return fac, _unit(fac.solve(e) / scale)


def natural_then_arclength(fun: Callable, dfun_ds: Callable, z0: np.ndarray, grid: np.ndarray,
                           scale: Callable, steps: StepControl, tol: float, max_iter: int,
                           accept: Callable | None = None, s_start: float | None = None,
                           on_failure: Callable[[], bool] | None = None,
                           jump_mask: np.ndarray | None = None,
                           max_points: int | None = None, floor: float | None = None) -> NaturalResult:
    """:func:`natural`, and where it stops, pseudo-arc-length continuation of ``r(z, s) = 0`` in
    ``x = [z, s]`` from its last accepted point, oriented towards increasing ``s``: it follows the
    branch through folds in ``s`` (where natural continuation must stop). Each remaining grid
    value is solved exactly, at fixed ``s``, from the secant interpolant between the two branch
    points that first bracket it (the first crossing along the branch; after a fold the branch
    may cross a value three times); the solution is trusted only if it fits the bracket (the
    geometry tests of the module docstring on both halves of the bracket), otherwise the bracket
    is bisected on the branch (a corrector on the hyperplane normal to the bracket's chord
    through its midpoint) and the solve repeated from the half that brackets the value, down to
    ``steps.minimum`` (:class:`NaturalThenArclength`). Points keep statuses and reasons as in
    :func:`natural`; ``branch`` holds every accepted point of both parts (``s`` then not
    monotone). Arc length is measured on ``[z/(√n·scale(z)), s]``: the RMS relative change of the
    unknowns and the change of ``s`` weigh alike, except the unknowns outside ``jump_mask``, which
    weigh ``FREE_WEIGHT``. ``max_points`` bounds the arc-length points (default
    ``400·max(1, 0.5 / steps.maximum)``, so that a smaller maximum step does not run out of
    points). ``floor``: the arc-length part stops where the branch, past a fold, turns back below
    ``s = floor`` (None: it follows the branch until ``max_points``); a caller that wants the branch
    through one point continued to values above it passes that point's ``s``: a value reached only
    after the branch came back past its start lies on another sheet."""
    grid = np.asarray(grid, float)
    out = natural(fun, dfun_ds, z0, grid, scale, steps, tol, max_iter, accept=accept,
                  s_start=s_start, on_failure=on_failure, jump_mask=jump_mask)
    todo = np.flatnonzero(out.status == Status.NO_CONVERGENCE)
    if not todo.size or not out.branch:                  # complete, or no start point
        return out
    if max_points is None:
        max_points = int(400 * max(1.0, 0.5 / steps.maximum))
    past_fold = NaturalThenArclength(fun, dfun_ds, scale, steps, tol, max_iter, out, int(todo[0]),
                                     accept, jump_mask, floor)
    past_fold.run(on_failure, max_points)
    return out


class NaturalThenArclength:
    """The arc-length part of :func:`natural_then_arclength`. Pseudo-arc-length continuation
    (:func:`arclength`, Allgower & Georg 2003, ch. 6, with its step control and geometry tests)
    of ``r(x) = r(z, s) = 0`` in ``x = [z, s]`` (:meth:`residual`: the Jacobian bordered by
    ``∂r/∂s``; :meth:`scaling`: the arc-length metric) from the last accepted point of the
    natural run ``out``, towards increasing ``s``. Every accepted point (:meth:`accept_point`)
    solves the grid values it passed at fixed ``s`` (:meth:`solve_grid_value`), bisecting the
    bracket on the branch where the solution does not fit it (:meth:`bisect`); :meth:`run` then
    gives the values left unsolved their statuses. State: ``previous``, the last accepted branch
    point; ``next``, the index of the first grid value not yet solved; ``why``, why a grid solve
    failed or the branch turned back below ``floor`` ("" if neither); ``peak``, the largest ``s``
    reached."""

    #: A grid solution is trusted within this many bracket lengths of the secant interpolant (an
    #: arc that turns by θ ≤ ``max_angle`` stays within θ/8 of its chord).
    BRACKET_FIT = 0.25

    def __init__(self, fun: Callable, dfun_ds: Callable, scale: Callable, steps: StepControl,
                 tol: float, max_iter: int, out: NaturalResult, first_missing: int,
                 accept: Callable | None, jump_mask: np.ndarray | None, floor: float | None = None):
        self.fun, self.dfun_ds, self.scale, self.steps = fun, dfun_ds, scale, steps
        self.floor = floor
        self.tol, self.max_iter, self.out, self.accept = tol, max_iter, out, accept
        self.first = out.branch[-1]
        self.root_n = np.sqrt(self.first.z.size)
        self.mask = None if jump_mask is None else np.r_[jump_mask, True]
        self.keep = slice(None) if self.mask is None else self.mask
        self.start = first_missing
        self.next = first_missing
        self.previous = np.r_[self.first.z, self.first.s]
        self.why = ""
        self.peak = self.first.s

    def run(self, on_failure: Callable[[], bool] | None, max_points: int) -> None:
        """Arc length from the natural run's last point towards increasing ``s`` until every grid
        value is solved, then the statuses of the values left unsolved."""
        x0 = self.previous
        grid = self.out.grid
        direction = np.zeros(x0.size)
        direction[-1] = 1.0
        run = arclength(self.residual, x0, direction, self.scaling(x0), self.steps, self.tol,
                        self.max_iter, stop=lambda x: self.next >= grid.size,
                        max_points=max_points, rescale=self.scaling, accept=self.accept_point,
                        on_failure=on_failure, jump_mask=self.mask)
        unfilled = [j for j in range(self.start, grid.size) if self.out.points[j] is None]
        why = self.why or f"arc length from s={self.first.s:.6g}: {run.reason}"
        _stopped(self.out, unfilled, why, "continuation stopped")

    def residual(self, x, jac):
        """``r(z, s)`` at ``x = [z, s]`` and its Jacobian ``[∂r/∂z, ∂r/∂s]``."""
        r, J, trivial, n_core, payload = self.fun(x[:-1], x[-1], jac)
        Jx = bordered(J, columns=self.dfun_ds(x[:-1], x[-1])) if jac else None
        return r, Jx, trivial, n_core, payload

    def scaling(self, x, _previous=None):
        """Arc-length scaling at ``x`` (the previous scaling is not needed); unknowns outside
        ``jump_mask`` weigh ``FREE_WEIGHT``."""
        sc = np.r_[self.root_n * self.scale(x[:-1]), 1.0]
        if self.mask is not None:
            sc[~self.mask] /= FREE_WEIGHT
        return sc

    def accept_point(self, x, payload):
        """Accepted arc-length point: record it, then solve the grid values it passed."""
        if self.accept is not None:
            self.accept(x[:-1], payload)
        if x is self.previous:                            # the start point, already recorded
            return
        out, grid = self.out, self.out.grid
        out.branch.append(ContinuationPoint(x[-1], x[:-1], payload, 0))
        self.peak = max(self.peak, x[-1])
        if self.floor is not None and x[-1] < self.floor:
            self.why = f"the branch turns back (fold at s={self.peak:.6g}) below s={self.floor:.6g}"
            self.next = grid.size                            # stop; statuses set by run
            return
        xa = self.previous
        while self.next < grid.size and xa[-1] < grid[self.next] <= x[-1]:
            k, sk = self.next, grid[self.next]
            res, self.why = self.solve_grid_value(sk, xa, x)
            if res is None:
                self.next = grid.size                        # stop; statuses set by run
                break
            _record(out, k, sk, res, None)
            self.next += 1
        self.previous = x

    def solve_grid_value(self, sk, xa, xb):
        """Grid value ``sk`` between the branch points ``xa``, ``xb``, by Newton at fixed ``s``
        from the secant interpolant: ``(NewtonResult, "")`` or ``(None, why)``. Trusted within
        :attr:`BRACKET_FIT` bracket lengths of the interpolant, otherwise the bracket is bisected
        on the branch and the half that brackets ``sk`` tried, down to ``steps.minimum``."""
        sc = self.scaling(xa)
        while True:
            w = (sk - xa[-1]) / (xb[-1] - xa[-1])
            guess = (1 - w) * xa + w * xb
            res = newton(lambda zz, jj: self.fun(zz, sk, jj), guess[:-1], self.scale, self.tol,
                         self.max_iter)
            length = np.linalg.norm(((xb - xa) / sc)[self.keep])
            if res.converged:
                off = np.linalg.norm(((np.r_[res.z, sk] - guess) / sc)[self.keep])
                if off <= self.BRACKET_FIT * length:
                    return res, ""
                why = f"solution {off / length:.3g} bracket lengths off the secant"
            else:
                why = res.reason
            if length < self.steps.minimum:
                return None, f"re-solve at grid s={sk:.6g}: {why}"
            xm = self.bisect(xa, xb, sc)
            if xm is None:
                return None, f"re-solve at grid s={sk:.6g}: bisection of the bracket failed"
            if (xm[-1] - sk) * (xa[-1] - sk) <= 0:      # the first half brackets sk
                xb = xm
            else:
                xa = xm

    def bisect(self, xa, xb, sc):
        """Branch point between ``xa`` and ``xb``: corrector on the hyperplane normal to their
        chord through its midpoint (None if it fails or leaves the bracket)."""
        chord = (xb - xa) / sc
        plane, mid = chord / sc, 0.5 * (xa + xb)

        def on_plane(xx, jac):
            r, J, trivial, n_core, payload = self.residual(xx, jac)
            Jb = bordered(J, rows=plane) if jac else None
            return np.append(r, plane @ (xx - mid)), Jb, trivial, n_core, payload

        res = newton(on_plane, mid, lambda _: sc, self.tol, self.max_iter)
        ok = res.converged and np.linalg.norm((res.z - mid) / sc) <= np.linalg.norm(chord)
        return res.z if ok else None
