"""Predictor–corrector continuation: natural parameter (log α for the dNNM), pseudo-arc-length
(excitation frequency for the forced response) and their combination (natural, then arc length
past a fold in the parameter, :func:`natural_then_arclength`), after Allgower & Georg,
*Introduction to Numerical Continuation Methods* (2003), ch. 6 (step-length adaptation).

Common rules. Tangent predictor, Newton corrector reusing the last factorisation while it
contracts (:func:`ringdamper.nonlinear.solvers.newton.newton`). Every accepted point gets a fresh
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
region of contraction, see :func:`ringdamper.nonlinear.solvers.newton.newton`). ``jump_mask`` restricts
the geometry to the unknowns that identify the branch (the EPMC leaves out the mean values, which
move freely where the last contact holding a rigid-body motion lets go). Failures never raise:
they end the run with a status (:class:`ringdamper.status.Status`). A natural step that ends
between two grid values may stop its corrector earlier (:attr:`StepControl.between`): such a point
carries only the predictor and the next step's geometry; every grid value is solved to the run's
tolerance.

Interface. A driver takes a *problem* and a :class:`StepControl` (every step setting, the corrector's
tolerance and Jacobian budget included). :func:`natural` and :func:`natural_then_arclength` take a
:class:`ParameterProblem` (``r(z, s) = 0``), :func:`arclength` a :class:`CurveProblem` (``r(x) = 0``,
one equation fewer than unknowns); both return an :class:`ringdamper.nonlinear.solvers.jacobian.Evaluation`
from ``fun`` and take the history hooks ``accept`` (every accepted point) and ``on_failure`` (after a
failed corrector). :class:`ParameterFunctions` and :class:`CurveFunctions` make one of plain functions.
A problem that carries state between evaluations (the gauge of the condensed HBM) holds it itself
(:class:`ringdamper.nonlinear.harmonic_balance.epmc.EPMCProblem`): the drivers keep none.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable, Protocol

import numpy as np

from ringdamper.nonlinear.solvers import krylov
from ringdamper.nonlinear.solvers.jacobian import Evaluation, dense, is_operator
from ringdamper.nonlinear.solvers.newton import Factorization, NewtonResult, linear_solver, newton
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


@dataclass(frozen=True)
class StepControl:
    """Step-size rules (in the continuation parameter or arc length). ``turn`` [rad]: nominal
    angle between the tangents of successive points (the step follows the curvature); a step
    whose tangent turns by more than twice that is rejected and halved (module docstring).
    ``between``: looser corrector tolerance of the natural steps that end between grid values
    (:meth:`corrector_tolerance`; None: the run's tolerance everywhere). ``give_up_damping``: a
    corrector whose damped Newton step needs ``λ`` at or below it fails its step at once (module
    docstring; None: only :attr:`corrector` ends it). ``quasi_newton``: the correctors take good
    Broyden steps on their factorisation instead of chord steps
    (:func:`ringdamper.nonlinear.solvers.newton.newton`).
    ``tangent_rtol``: accuracy (scaled 2-norm) of the arc-length tangents that GMRES solves on a
    lagged LU (:mod:`ringdamper.nonlinear.solvers.krylov`). ``tol``, ``max_iter``: Newton tolerance of a
    converged point (scaled step, :func:`ringdamper.nonlinear.solvers.newton.newton`) and its fresh Jacobians.
    ``max_angle``: the geometry tests' angle (None: ``2·turn``, :meth:`angle_limit`); ``corner``: the
    turn test is waived below ``corner × minimum``. ``max_points``: arc-length points of a run (None:
    :meth:`arc_points`)."""

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
    tol: float = 1e-8           # Newton tolerance of a converged point
    max_iter: int = 20          # fresh Jacobians of a Newton solve
    max_angle: float | None = None  # angle of the geometry tests (None: 2 turn)
    corner: float = 100.0       # the turn test is waived below corner × minimum
    max_points: int | None = None   # arc-length points of a run (None: arc_points' default)

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

    def angle_limit(self) -> float:
        """The geometry tests' angle [rad]: :attr:`max_angle`, default ``2·turn``."""
        return 2 * self.turn if self.max_angle is None else self.max_angle

    def arc_points(self) -> int:
        """Arc-length points of a run: :attr:`max_points`, default ``400·max(1, 0.5 / maximum)`` (so that
        a smaller maximum step does not run out of points)."""
        return int(400 * max(1.0, 0.5 / self.maximum)) if self.max_points is None else self.max_points

    def corrector_tolerance(self, ds: float, on_grid: bool) -> float:
        """Newton tolerance of a natural step of size ``ds``: :attr:`tol` on a grid value; between grid
        values, where a point only carries the predictor and the step's geometry, up to
        :attr:`between`, and at most ``BETWEEN_PER_STEP·ds`` so that the corrector's error tilts
        the chord by no more than that angle [rad] (``|δu| ≤ tol``, chord ``≥ ds``; the geometry
        tests work at 0.1–0.2 rad)."""
        if on_grid or self.between is None:
            return self.tol
        return max(self.tol, min(self.between, BETWEEN_PER_STEP * ds))

    def corrector_iterations(self) -> int:
        """Fresh Jacobians a predictor–corrector step may use: :attr:`corrector`, at most :attr:`max_iter`."""
        return self.max_iter if self.corrector is None else min(self.corrector, self.max_iter)

    def adapt(self, ds: float, res, turn: float = 0.0) -> float:
        """New step from the corrector's effort (Jacobians + iterations / chord budget, see
        :func:`ringdamper.nonlinear.solvers.newton.newton`: cheap chord iterations count little) and the
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


class ParameterProblem(Protocol):
    """``r(z, s) = 0`` in the unknowns ``z`` and the scalar parameter ``s`` (:func:`natural`):
    ``fun(z, s, jacobian)`` its :class:`ringdamper.nonlinear.solvers.jacobian.Evaluation`, ``dfun_ds(z, s)``
    ``∂r/∂s``, ``scale(z)`` the unknowns' convergence scales; ``accept(z, payload)`` is called on every
    accepted point (history updates, e.g. a gauge), ``on_failure()`` after a failed corrector (True:
    the problem changed, e.g. a rigid-body direction was pinned, and the same step is tried again);
    ``jump_mask``: the unknowns the step geometry looks at (None: all)."""

    jump_mask: np.ndarray | None

    def fun(self, z: np.ndarray, s: float, jacobian: bool) -> Evaluation: ...

    def dfun_ds(self, z: np.ndarray, s: float) -> np.ndarray: ...

    def scale(self, z: np.ndarray) -> np.ndarray: ...

    def accept(self, z: np.ndarray, payload) -> None: ...

    def on_failure(self) -> bool: ...


class CurveProblem(Protocol):
    """``r(x) = 0`` with one equation fewer than unknowns (:func:`arclength`): ``fun(x, jacobian)``,
    ``accept``, ``on_failure`` and ``jump_mask`` as in :class:`ParameterProblem`; ``stop(x)``: the run
    ends at the accepted point ``x``; ``rescale(x, scale)``: the arc-length scaling after the accepted
    point ``x`` (None: keep ``scale``)."""

    jump_mask: np.ndarray | None

    def fun(self, x: np.ndarray, jacobian: bool) -> Evaluation: ...

    def accept(self, x: np.ndarray, payload) -> None: ...

    def on_failure(self) -> bool: ...

    def stop(self, x: np.ndarray) -> bool: ...

    def rescale(self, x: np.ndarray, scale: np.ndarray) -> np.ndarray | None: ...


def _no_history(*_args) -> None:
    """An ``accept`` that keeps no history."""


def _unchanged() -> bool:
    """An ``on_failure`` that changes nothing (the failed step is halved)."""
    return False


def _keep_scale(_x, _scale) -> None:
    """A ``rescale`` that keeps the scaling."""
    return None


@dataclass(frozen=True)
class ParameterFunctions:
    """A :class:`ParameterProblem` of plain functions (tests, studies)."""

    fun: Callable[[np.ndarray, float, bool], Evaluation]
    dfun_ds: Callable[[np.ndarray, float], np.ndarray]
    scale: Callable[[np.ndarray], np.ndarray]
    accept: Callable = _no_history
    on_failure: Callable[[], bool] = _unchanged
    jump_mask: np.ndarray | None = None


@dataclass(frozen=True)
class CurveFunctions:
    """A :class:`CurveProblem` of plain functions (tests, studies)."""

    fun: Callable[[np.ndarray, bool], Evaluation]
    stop: Callable[[np.ndarray], bool]
    rescale: Callable = _keep_scale
    accept: Callable = _no_history
    on_failure: Callable[[], bool] = _unchanged
    jump_mask: np.ndarray | None = None


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



@dataclass
class _Trusted:
    """The last trusted point of a natural run: parameter ``s``, unknowns ``z``, tangent ``dz/ds`` and
    the solver the next corrector starts from."""

    s: float
    z: np.ndarray
    tangent: np.ndarray
    fac: Any


def natural(problem: ParameterProblem, z0: np.ndarray, grid: np.ndarray, steps: StepControl,
            s_start: float | None = None) -> NaturalResult:
    """Continuation of ``problem`` in the scalar parameter ``s`` from ``s_start`` (default ``grid[0]``;
    ``z0`` is the guess there) over the increasing ``grid``, landing exactly on every grid value (so grid
    outputs are converged solutions, not interpolants).

    Tangents: at a grid value from the LU of its Jacobian, equilibrated, whose condition estimate the
    point keeps (:attr:`ContinuationPoint.condition`); between grid values by GMRES on the corrector's
    last LU (:func:`ringdamper.nonlinear.solvers.newton.linear_solver`). Either way the next corrector starts
    from the corrector's own chain of LUs, not from the grid value's exact one: handed on, that LU
    made correctors cheaper, the step control then grew the steps into the stretch where pairs lift
    off, and one ring of twenty (t036 of the paper design) took twice as long and lost its top point
    (docs/nonlinear_core.md §4.6).

    ``problem.accept`` is called on every accepted point, ``problem.on_failure`` after a failed
    corrector (:class:`ParameterProblem`). The step geometry (module docstring) is measured on
    ``u = [z/(√n·scale(z₀)), s]`` with the tangent ``(dz/ds, 1)`` of every accepted point, over the
    unknowns ``problem.jump_mask``; in addition a step is rejected when the tangent oriented along the
    chord points to decreasing ``s`` (a fold in ``s`` between the two points, which natural continuation
    cannot pass).
    """
    grid = np.asarray(grid, float)
    n = grid.size
    out = NaturalResult(grid, [None] * n, np.full(n, Status.NOT_REACHED, int), ["not reached"] * n)
    s = grid[0] if s_start is None else min(s_start, grid[0])
    res = newton(lambda z, jac: problem.fun(z, s, jac), z0, problem.scale, steps.tol, steps.max_iter)
    if not res.converged:
        out.status[0], out.reason[0] = Status.NO_CONVERGENCE, f"start point: {res.reason}"
        return out
    on_grid = s == grid[0]
    fac_t, tangent = _natural_tangent(problem, res.z, s, res.factorization, exact=on_grid)
    front, gi = _accept_natural(problem, out, 0, s, res, tangent, fac_t, on_grid)
    mask = None if problem.jump_mask is None else np.r_[problem.jump_mask, True]
    root_n = np.sqrt(z0.size)
    ds = steps.initial
    while gi < n:
        s_t = min(front.s + ds, grid[gi])
        on_grid = s_t >= grid[gi] - 1e-12 * max(1.0, abs(grid[gi]))
        s_t = grid[gi] if on_grid else s_t
        res, tangent_t, fac_t, geometry, why = _natural_step(problem, steps, front, s_t, on_grid,
                                                             root_n, mask)
        if not why:
            front, gi = _accept_natural(problem, out, gi, s_t, res, tangent_t, fac_t, on_grid)
            ds = steps.adapt(ds, res, geometry[0])
            continue
        if problem.on_failure():
            continue
        ds = 0.5 * (s_t - front.s)
        if ds < steps.minimum:
            _stopped(out, range(gi, n), f"step below minimum at s={front.s:.6g}: {why}",
                     f"continuation stopped at s={front.s:.6g}")
            break
    return out


def _natural_step(problem: ParameterProblem, steps: StepControl, front: _Trusted, s_t: float,
                  on_grid: bool, root_n: float, mask):
    """Predictor from ``front`` to ``s_t`` and its corrector, with the step's tests (module docstring):
    ``(result, tangent, solver, geometry, why)`` (``why`` "" for a trusted step)."""
    z_pred = front.z + (s_t - front.s) * front.tangent
    res = newton(lambda zz, jac: problem.fun(zz, s_t, jac), z_pred, problem.scale,
                 steps.corrector_tolerance(s_t - front.s, on_grid), steps.corrector_iterations(),
                 factorization=front.fac, give_up_damping=steps.give_up_damping,
                 quasi_newton=steps.quasi_newton)
    if not res.converged:
        return res, None, None, None, res.reason
    fac_t, tangent_t = _natural_tangent(problem, res.z, s_t, res.factorization, exact=on_grid)
    geometry, fold = _natural_geometry(front.z, front.s, front.tangent, res.z, s_t, tangent_t,
                                       root_n * problem.scale(front.z), mask)
    why = ("fold in s between the points" if fold else
           _untrusted(geometry, steps.angle_limit(), s_t - front.s <= steps.corner * steps.minimum))
    return res, tangent_t, fac_t, geometry, why


def _accept_natural(problem: ParameterProblem, out: NaturalResult, gi: int, s: float, res: NewtonResult,
                    tangent: np.ndarray, fac_t, on_grid: bool) -> tuple[_Trusted, int]:
    """Accept the point ``res`` at ``s`` (tangent ``tangent`` from the solver ``fac_t``): on the branch,
    and solved for grid value ``gi`` if ``on_grid``; the new trusted point and the next grid index."""
    out.branch.append(ContinuationPoint(s, res.z, res.payload, res.iterations))
    if on_grid:
        _record(out, gi, s, res, fac_t)
        gi += 1
    problem.accept(res.z, res.payload)
    return _Trusted(s, res.z, tangent, res.factorization if on_grid else fac_t), gi


def _natural_geometry(z0, s0, tangent0, z1, s1, tangent1, w, mask):
    """Geometry (:func:`_step_geometry`) of the natural step from ``(z0, s0)`` to ``(z1, s1)``
    in ``u = [z/w, s]`` with the tangents ``(dz/ds, 1)`` at both ends, and whether the end
    tangent oriented along the chord points to decreasing ``s`` (a fold in ``s`` between them)."""
    chord = np.append((z1 - z0) / w, s1 - s0)
    t0, t1 = _unit(np.append(tangent0 / w, 1.0)), _unit(np.append(tangent1 / w, 1.0))
    if t1 @ chord < 0:
        t1 = -t1
    return _step_geometry(t0, t1, chord, mask), t1[-1] <= 0


def _natural_tangent(problem: ParameterProblem, z, s, previous, exact=False):
    """Solver of the Jacobian at ``(z, s)`` and the tangent ``dz/ds = −J⁻¹ ∂r/∂s``. The solver is
    :func:`ringdamper.nonlinear.solvers.newton.linear_solver` on the factorisation of the solver ``previous``
    or, with ``exact``, the LU of the Jacobian itself, equilibrated by the scales ``scale(z)``, which
    gives the point its condition estimate (:meth:`ringdamper.nonlinear.solvers.newton.Factorization.condition`)."""
    ev = problem.fun(z, s, True)
    if exact:
        fac = Factorization(dense(ev.J), ev.trivial, ev.n_core, overwrite=is_operator(ev.J),
                            scale=problem.scale(z))
    else:
        fac = linear_solver(ev.J, ev.trivial, ev.n_core, previous, 1.0 / problem.scale(z))
    return fac, fac.solve(-problem.dfun_ds(z, s))


def _record(out: NaturalResult, i: int, s: float, res: NewtonResult, fac=None):
    """Grid value ``i`` solved: ``res`` at ``s``, with the condition estimate of ``fac``, the exact
    factorisation of its Jacobian (:func:`_natural_tangent`), if given."""
    condition = np.nan if fac is None else fac.condition()
    out.points[i] = ContinuationPoint(s, res.z, res.payload, res.iterations, condition)
    out.status[i], out.reason[i] = Status.CONVERGED, ""


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


def arclength(problem: CurveProblem, z0: np.ndarray, direction: np.ndarray, scale: np.ndarray,
              steps: StepControl) -> ArclengthResult:
    """Pseudo-arc-length continuation of ``problem`` (:class:`CurveProblem`, one fewer equation than
    unknowns, its Jacobian of shape ``(n−1, n)``) from the solution ``z0``, oriented along
    ``direction``; ``scale`` the variable scaling (arc length is measured on ``u = z / scale``; the
    corrector stays on the hyperplane through the predictor normal to the tangent). Every accepted
    point gets its tangent from a fresh Jacobian (the null vector of ``J``, oriented along the chord of
    the step). A step is trusted by the geometry tests of the module docstring
    (:meth:`StepControl.angle_limit`; the turn test is waived below ``steps.corner × steps.minimum``,
    the chord–tangent consistency test never) and otherwise halved from the last trusted point. Stops
    with status 0 at an accepted point where ``problem.stop`` is true, after
    :meth:`StepControl.arc_points` points with MAX_POINTS. ``problem.rescale`` may update the scaling
    after every accepted point (the tangent is carried over in unscaled form); ``problem.accept`` is
    called on the start and every accepted point (history updates). ``tangents`` and ``scales`` in the
    result hold the unit tangent (in ``u``) and the scaling in force at every point.
    """
    ev0 = problem.fun(z0, True)
    problem.accept(z0, ev0.payload)
    last_fac, t = _tangent(ev0, direction / scale, scale, None)
    pts, tans, scales = [ContinuationPoint(0.0, z0, ev0.payload, 0)], [t], [scale]
    z, s, ds = z0, 0.0, steps.initial
    smallest = steps.corner * steps.minimum
    while len(pts) < steps.arc_points():
        step = _ArcStep(problem, steps, z, t, scale)
        res, t1, fac1, turn, why = step(t, ds, last_fac)
        if why and ds <= smallest:
            turned = _turn_corner(step, ds, smallest)
            if turned:
                ds, (res, t1, fac1, turn, why) = turned
        if not why:
            z, t, s, last_fac = res.z, t1, s + ds, fac1
            pts.append(ContinuationPoint(s, z, res.payload, res.iterations))
            tans.append(t)
            scales.append(scale)
            problem.accept(z, res.payload)
            if problem.stop(z):
                return ArclengthResult(pts, tans, scales, Status.CONVERGED, "")
            new = problem.rescale(z, scale)
            if new is not None:
                t, scale = _unit(t * scale / new), new
            ds = steps.adapt(ds, res, turn)
            continue
        if problem.on_failure():
            continue
        ds *= 0.5
        if ds < steps.minimum:
            return ArclengthResult(pts, tans, scales, Status.NO_CONVERGENCE, f"step below minimum: {why}")
    return ArclengthResult(pts, tans, scales, Status.MAX_POINTS, f"{steps.arc_points()} points reached")


@dataclass
class _ArcStep:
    """One arc-length step from the trusted point ``z`` (unit tangent ``t`` in ``u = z / scale``)."""

    problem: CurveProblem
    steps: StepControl
    z: np.ndarray
    t: np.ndarray
    scale: np.ndarray

    def __call__(self, d, ds, fac):
        """Corrector from ``z + ds·d`` on the hyperplane normal to ``d`` (scaled), and the tests
        against the trusted tangent ``t``: ``(result, tangent, factorisation, turn, why)``."""
        z, scale, steps = self.z, self.scale, self.steps
        zp, plane = z + ds * d * scale, d / scale

        def on_plane(zz, jac):
            return self.problem.fun(zz, jac).extended(plane @ (zz - zp), rows=plane)

        res = newton(on_plane, zp, lambda _: scale, steps.tol, steps.corrector_iterations(), factorization=fac,
                     give_up_damping=steps.give_up_damping, quasi_newton=steps.quasi_newton)
        if not res.converged:
            return res, None, None, 0.0, res.reason
        chord = (res.z - z) / scale
        fac1, t1 = _tangent(self.problem.fun(res.z, True), chord, scale, res.factorization,
                            steps.tangent_rtol)
        geometry = _step_geometry(self.t, t1, chord, self.problem.jump_mask)
        why = _untrusted(geometry, steps.angle_limit(), ds <= steps.corner * steps.minimum)
        if not why and _angle(-self.t, chord) <= np.pi / 4:
            why = "corrector went back along the branch"
        return res, t1, fac1, geometry[0], why


def _turn_corner(step: _ArcStep, ds, largest):
    """Past a corner of a piecewise-smooth branch where it turns back (by more than 90°), the
    hyperplane normal to the incoming tangent ``t`` misses the outgoing branch. Its direction is
    the null vector of the Jacobian just past the corner (at the predictor ``z + ds·t``); both
    orientations are tried as predictor directions with steps ``ds``, ``4·ds``, … up to
    ``largest``; each must pass :func:`arclength`'s tests (and not lead back along the incoming
    branch). Returns ``step``'s tuple, or None."""
    z, t, scale = step.z, step.t, step.scale
    fac, ahead = _tangent(step.problem.fun(z + ds * t * scale, True), t, scale, None)
    sizes = [ds * 4.0 ** k for k in range(int(np.log(largest / ds) / np.log(4.0)) + 1)]
    for size in sizes:
        for d in (ahead, -ahead):
            trial = step(d, size, fac)
            if not trial[-1]:
                return size, trial
    return None


def _tangent(ev: Evaluation, direction_u, scale, previous, rtol=krylov.RTOL):
    """Solver of the Jacobian of ``ev`` bordered by ``direction_u / scale``
    (:func:`ringdamper.nonlinear.solvers.newton.linear_solver`, on the factorisation of the solver ``previous``,
    if any, to ``rtol``) and the unit tangent in scaled variables: ``J (scale·t) = 0``, oriented along
    ``direction_u``."""
    e = np.zeros(ev.J.shape[1])
    e[-1] = 1.0
    bordered = ev.extended(rows=direction_u / scale)
    fac = linear_solver(bordered.J, ev.trivial, ev.n_core, previous, 1.0 / scale, rtol)
    return fac, _unit(fac.solve(e) / scale)


def natural_then_arclength(problem: ParameterProblem, z0: np.ndarray, grid: np.ndarray, steps: StepControl,
                           s_start: float | None = None, floor: float | None = None) -> NaturalResult:
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
    unknowns and the change of ``s`` weigh alike, except the unknowns outside ``problem.jump_mask``,
    which weigh ``FREE_WEIGHT``. The arc-length points are bounded by :meth:`StepControl.arc_points`.
    ``floor``: the arc-length part stops where the branch, past a fold, turns back below
    ``s = floor`` (None: it follows the branch until its points run out); a caller that wants the
    branch through one point continued to values above it passes that point's ``s``: a value reached
    only after the branch came back past its start lies on another sheet."""
    grid = np.asarray(grid, float)
    out = natural(problem, z0, grid, steps, s_start=s_start)
    todo = np.flatnonzero(out.status == Status.NO_CONVERGENCE)
    if not todo.size or not out.branch:                  # complete, or no start point
        return out
    NaturalThenArclength(problem, steps, out, int(todo[0]), floor).run()
    return out


class NaturalThenArclength:
    """The arc-length part of :func:`natural_then_arclength`, a :class:`CurveProblem`. Pseudo-arc-length
    continuation (:func:`arclength`, Allgower & Georg 2003, ch. 6, with its step control and geometry
    tests) of ``r(x) = r(z, s) = 0`` in ``x = [z, s]`` (:meth:`fun`: the Jacobian bordered by
    ``∂r/∂s``; :meth:`rescale`: the arc-length metric) from the last accepted point of the
    natural run ``out``, towards increasing ``s``. Every accepted point (:meth:`accept`)
    solves the grid values it passed at fixed ``s`` (:meth:`solve_grid_value`), bisecting the
    bracket on the branch where the solution does not fit it (:meth:`bisect`); :meth:`run` then
    gives the values left unsolved their statuses. State: ``previous``, the last accepted branch
    point; ``next``, the index of the first grid value not yet solved; ``why``, why a grid solve
    failed or the branch turned back below ``floor`` ("" if neither); ``peak``, the largest ``s``
    reached."""

    #: A grid solution is trusted within this many bracket lengths of the secant interpolant (an
    #: arc that turns by θ ≤ ``max_angle`` stays within θ/8 of its chord).
    BRACKET_FIT = 0.25

    def __init__(self, problem: ParameterProblem, steps: StepControl, out: NaturalResult,
                 first_missing: int, floor: float | None = None):
        self.problem, self.steps, self.out, self.floor = problem, steps, out, floor
        self.first = out.branch[-1]
        self.root_n = np.sqrt(self.first.z.size)
        self.jump_mask = None if problem.jump_mask is None else np.r_[problem.jump_mask, True]
        self.keep = slice(None) if self.jump_mask is None else self.jump_mask
        self.start = first_missing
        self.next = first_missing
        self.previous = np.r_[self.first.z, self.first.s]
        self.why = ""
        self.peak = self.first.s

    def run(self) -> None:
        """Arc length from the natural run's last point towards increasing ``s`` until every grid
        value is solved, then the statuses of the values left unsolved."""
        x0 = self.previous
        grid = self.out.grid
        direction = np.zeros(x0.size)
        direction[-1] = 1.0
        run = arclength(self, x0, direction, self.rescale(x0), self.steps)
        unfilled = [j for j in range(self.start, grid.size) if self.out.points[j] is None]
        why = self.why or f"arc length from s={self.first.s:.6g}: {run.reason}"
        _stopped(self.out, unfilled, why, "continuation stopped")

    def fun(self, x, jac) -> Evaluation:
        """``r(z, s)`` at ``x = [z, s]`` and its Jacobian ``[∂r/∂z, ∂r/∂s]``."""
        ev = self.problem.fun(x[:-1], x[-1], jac)
        return ev.extended(columns=self.problem.dfun_ds(x[:-1], x[-1]) if jac else None)

    def rescale(self, x, _previous=None):
        """Arc-length scaling at ``x`` (the previous scaling is not needed); unknowns outside
        ``jump_mask`` weigh ``FREE_WEIGHT``."""
        sc = np.r_[self.root_n * self.problem.scale(x[:-1]), 1.0]
        if self.jump_mask is not None:
            sc[~self.jump_mask] /= FREE_WEIGHT
        return sc

    def on_failure(self) -> bool:
        return self.problem.on_failure()

    def stop(self, _x) -> bool:
        """Every grid value solved, or the run given up (:meth:`accept`)."""
        return self.next >= self.out.grid.size

    def accept(self, x, payload):
        """Accepted arc-length point: record it, then solve the grid values it passed."""
        self.problem.accept(x[:-1], payload)
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
            _record(out, k, sk, res)
            self.next += 1
        self.previous = x

    def solve_grid_value(self, sk, xa, xb):
        """Grid value ``sk`` between the branch points ``xa``, ``xb``, by Newton at fixed ``s``
        from the secant interpolant: ``(NewtonResult, "")`` or ``(None, why)``. Trusted within
        :attr:`BRACKET_FIT` bracket lengths of the interpolant, otherwise the bracket is bisected
        on the branch and the half that brackets ``sk`` tried, down to ``steps.minimum``."""
        sc = self.rescale(xa)
        while True:
            w = (sk - xa[-1]) / (xb[-1] - xa[-1])
            guess = (1 - w) * xa + w * xb
            res = newton(lambda zz, jj: self.problem.fun(zz, sk, jj), guess[:-1], self.problem.scale,
                         self.steps.tol, self.steps.max_iter)
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
            return self.fun(xx, jac).extended(plane @ (xx - mid), rows=plane)

        res = newton(on_plane, mid, lambda _: sc, self.steps.tol, self.steps.max_iter)
        ok = res.converged and np.linalg.norm((res.z - mid) / sc) <= np.linalg.norm(chord)
        return res.z if ok else None
