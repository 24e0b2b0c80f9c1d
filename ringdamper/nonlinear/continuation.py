"""Predictor–corrector continuation: natural parameter (log α for the dNNM), pseudo-arc-length
(excitation frequency for the forced response) and their combination (natural, then arc length
past a fold in the parameter, :func:`natural_then_arclength`), after Allgower & Georg (2003).

Common rules: tangent predictor, Newton corrector reusing the last factorisation while it
contracts (:func:`ringdamper.nonlinear.newton.newton`), step grown ×1.5 when the corrector's effort
(Jacobians + chord iterations / 12) is at most 1.5 and halved above 4, halved on failure, and a
corrector that moves farther than its own predictor step (or than ``jump_floor`` in the scaled
norm) is rejected as a branch jump; ``jump_mask`` restricts that test to the unknowns that
identify the branch (the EPMC leaves out the mean values, which move freely where the last
contact holding a rigid-body motion lets go). Failures never raise: they end the run with a status.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from enum import IntEnum
from typing import Any, Callable

import numpy as np

from ringdamper.nonlinear.newton import Factorization, NewtonResult, newton


class Status(IntEnum):
    """Per-point status (0 = converged), stored with every result."""

    CONVERGED = 0
    NO_CONVERGENCE = 1       # step size fell below its minimum
    NOT_REACHED = 2          # continuation stopped before this point
    DRIFT = 3                # converged, but a free body is not in mean equilibrium (ratchets)
    MAX_POINTS = 4           # arc-length budget exhausted before the end of the range


@dataclass
class StepControl:
    """Step-size rules (in the continuation parameter or arc length)."""

    initial: float
    minimum: float
    maximum: float
    grow: float = 1.5
    easy: float = 1.5        # corrector effort (:attr:`NewtonResult.effort`) below which ds grows
    hard: float = 4.0        # effort above which ds shrinks
    jump_floor: float = 0.05

    def adapt(self, ds: float, res) -> float:
        """New step from the corrector's effort (Jacobians + iterations / chord budget, see
        :func:`ringdamper.nonlinear.newton.newton`): cheap chord iterations count little."""
        if res.effort <= self.easy:
            ds *= self.grow
        elif res.effort >= self.hard:
            ds *= 0.5
        return min(ds, self.maximum)


@dataclass
class ContinuationPoint:
    s: float
    z: np.ndarray
    payload: Any
    iterations: int


@dataclass
class NaturalResult:
    """Solutions at the requested parameter values (``None`` where not converged), their
    statuses and reasons, and every accepted point of the branch."""

    grid: np.ndarray
    points: list
    status: np.ndarray
    reason: list
    branch: list = field(default_factory=list)


def _moved(a, b, sc, mask=None):
    """Largest scaled difference ``max |a − b| / sc`` over the unknowns ``mask`` (default all)."""
    keep = slice(None) if mask is None else mask
    return np.max(np.abs(a - b)[keep] / sc[keep])


def _blocked(z_new, z_pred, z_old, scale, floor, mask=None):
    sc = scale(z_old)
    return _moved(z_new, z_pred, sc, mask) > max(_moved(z_pred, z_old, sc, mask), floor)


def natural(fun: Callable, dfun_ds: Callable, z0: np.ndarray, grid: np.ndarray,
            scale: Callable, steps: StepControl, tol: float, max_iter: int,
            accept: Callable | None = None, s_start: float | None = None,
            on_failure: Callable[[], bool] | None = None,
            jump_mask: np.ndarray | None = None) -> NaturalResult:
    """Continuation in the scalar parameter ``s`` from ``s_start`` (default ``grid[0]``; ``z0``
    is the guess there) over the increasing ``grid``, landing exactly on every grid value (so grid
    outputs are converged solutions, not interpolants).

    ``fun(z, s, jacobian) -> (r, J, trivial, n_core, payload)``; ``dfun_ds(z, s)`` is ``∂r/∂s``;
    ``accept(z, payload)`` is called on every accepted point (e.g. to update a gauge);
    ``on_failure()`` after a failed corrector: if it returns True the problem has changed (e.g. a
    rigid-body direction was pinned) and the same step is tried again before it is halved.
    ``jump_mask``: unknowns the branch-jump test looks at (default all).
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
    z, last = res.z, res
    out.branch.append(ContinuationPoint(s, z, res.payload, res.iterations))
    gi = 0
    if s == grid[0]:
        _record(out, 0, s, res, accept)
        gi = 1
    elif accept is not None:
        accept(z, res.payload)
    ds = steps.initial
    while gi < n:
        s_t = min(s + ds, grid[gi])
        on_grid = s_t >= grid[gi] - 1e-12 * max(1.0, abs(grid[gi]))
        s_t = grid[gi] if on_grid else s_t
        tangent = last.factorization.solve(-dfun_ds(z, s))
        z_pred = z + (s_t - s) * tangent
        res = newton(lambda zz, jac: fun(zz, s_t, jac), z_pred, scale, tol, max_iter,
                     factorization=last.factorization)
        if res.converged and not _blocked(res.z, z_pred, z, scale, steps.jump_floor, jump_mask):
            s, z, last = s_t, res.z, res
            out.branch.append(ContinuationPoint(s, z, res.payload, res.iterations))
            if on_grid:
                _record(out, gi, s, res, accept)
                gi += 1
            elif accept is not None:
                accept(z, res.payload)
            ds = steps.adapt(ds, res)
            continue
        if on_failure is not None and on_failure():
            continue
        ds = 0.5 * (s_t - s)
        if ds < steps.minimum:
            why = res.reason if not res.converged else "corrector jumped (possible branch switch)"
            for k in range(gi, n):
                status[k] = Status.NO_CONVERGENCE if k == gi else Status.NOT_REACHED
                reason[k] = (f"step below minimum at s={s:.6g}: {why}" if k == gi
                             else f"continuation stopped at s={s:.6g}")
            break
    return out


def _record(out: NaturalResult, i: int, s: float, res: NewtonResult, accept):
    out.points[i] = ContinuationPoint(s, res.z, res.payload, res.iterations)
    out.status[i], out.reason[i] = Status.CONVERGED, ""
    if accept is not None:
        accept(res.z, res.payload)


@dataclass
class ArclengthResult:
    points: list
    tangents: list
    scales: list
    status: int
    reason: str


def arclength(fun: Callable, z0: np.ndarray, direction: np.ndarray, scale: np.ndarray,
              steps: StepControl, tol: float, max_iter: int, stop: Callable[[np.ndarray], bool],
              max_points: int, max_angle: float = np.pi / 4, corner: float = 100.0,
              rescale: Callable | None = None, accept: Callable | None = None,
              on_failure: Callable[[], bool] | None = None,
              jump_mask: np.ndarray | None = None) -> ArclengthResult:
    """Pseudo-arc-length continuation of ``r(z) = 0`` (one fewer equation than unknowns).

    ``fun(z, jacobian) -> (r, J, trivial, n_core, payload)``, ``J`` of shape ``(n−1, n)``; ``z0`` a
    solution; ``direction`` the initial orientation; ``scale`` the variable scaling (arc length is
    measured on ``u = z / scale``; the corrector stays on the hyperplane normal to the tangent).
    The first tangent comes from the Jacobian, the next ones are secants of accepted steps.
    A step is rejected if the tangent turns by more than ``max_angle``, unless the step has
    already been refined below ``corner × steps.minimum``: the turn is then a corner of the
    non-smooth branch (e.g. the stick–slip kink of a Jenkins element). Stops with status 0 when
    ``stop(z)`` is true. ``rescale(z, scale) -> scale`` may update the scaling after every
    accepted point (the tangent is carried over in unscaled form); ``accept(z, payload)`` is
    called on the start and every accepted point (history updates). ``scales`` in the result holds
    the scaling in force at every point. ``on_failure()`` and ``jump_mask`` as in
    :func:`natural`.
    """
    r0, J0, trivial0, n_core0, payload0 = fun(z0, True)
    if accept is not None:
        accept(z0, payload0)
    t = _tangent(J0, trivial0, n_core0, direction / scale, scale)
    pts, tans, scales = [ContinuationPoint(0.0, z0, payload0, 0)], [t], [scale]
    z, s, ds = z0, 0.0, steps.initial
    last_fac = None
    while len(pts) < max_points:
        zp = z + ds * t * scale
        plane = t / scale

        def bordered(zz, jac, zp=zp, plane=plane):
            r, J, trivial, n_core, payload = fun(zz, jac)
            Jb = np.vstack([J, plane]) if jac else None
            return np.r_[r, plane @ (zz - zp)], Jb, trivial, n_core, payload

        res = newton(bordered, zp, lambda _: scale, tol, max_iter, factorization=last_fac)
        ok = res.converged and not _blocked(res.z, zp, z, lambda _: scale, steps.jump_floor,
                                            jump_mask)
        if ok:                                       # secant tangent of the accepted step
            x = (res.z - z) / scale
            t_new = x / np.linalg.norm(x)
            ok = np.dot(t_new, t) >= np.cos(max_angle) or ds <= corner * steps.minimum
        if ok:
            z, t, s, last_fac = res.z, t_new, s + ds, res.factorization
            pts.append(ContinuationPoint(s, z, res.payload, res.iterations))
            tans.append(t)
            scales.append(scale)
            if accept is not None:
                accept(z, res.payload)
            if stop(z):
                return ArclengthResult(pts, tans, scales, Status.CONVERGED, "")
            if rescale is not None:
                new = rescale(z, scale)
                t = t * scale / new
                t, scale = t / np.linalg.norm(t), new
            ds = steps.adapt(ds, res)
            continue
        if on_failure is not None and on_failure():
            continue
        ds *= 0.5
        if ds < steps.minimum:
            why = res.reason if not res.converged else "tangent turned or corrector jumped"
            return ArclengthResult(pts, tans, scales, Status.NO_CONVERGENCE,
                                   f"step below minimum: {why}")
    return ArclengthResult(pts, tans, scales, Status.MAX_POINTS, f"{max_points} points reached")


def _tangent(J, trivial, n_core, direction_u, scale):
    """Unit tangent in scaled variables: ``J (scale·t) = 0`` oriented along ``direction_u``."""
    e = np.zeros(J.shape[1])
    e[-1] = 1.0
    x = Factorization(np.vstack([J, direction_u / scale]), trivial, n_core).solve(e) / scale
    return x / np.linalg.norm(x)


def natural_then_arclength(fun: Callable, dfun_ds: Callable, z0: np.ndarray, grid: np.ndarray,
                           scale: Callable, steps: StepControl, tol: float, max_iter: int,
                           accept: Callable | None = None, s_start: float | None = None,
                           on_failure: Callable[[], bool] | None = None,
                           jump_mask: np.ndarray | None = None,
                           max_points: int = 400) -> NaturalResult:
    """:func:`natural`, and where it stops, pseudo-arc-length continuation of ``r(z, s) = 0`` in
    ``x = [z, s]`` from its last accepted point, oriented towards increasing ``s``: it follows the
    branch through folds in ``s`` (where natural continuation must stop). Each remaining grid
    value is solved exactly, at fixed ``s``, from the secant interpolant between the two branch
    points that first bracket it (the first crossing along the branch; after a fold the branch
    may cross a value three times), and accepted only if the solution stays within the bracket's
    distance of the interpolant (no branch jump). Points keep statuses and reasons as in
    :func:`natural`; ``branch`` holds every accepted point of both parts (``s`` then not
    monotone). Arc length is measured on ``[z/(√n·scale(z)), s]``: the RMS relative change of
    the unknowns and the change of ``s`` weigh alike."""
    out = natural(fun, dfun_ds, z0, grid, scale, steps, tol, max_iter, accept=accept,
                  s_start=s_start, on_failure=on_failure, jump_mask=jump_mask)
    todo = np.flatnonzero(out.status == Status.NO_CONVERGENCE)
    if not todo.size or not out.branch:                  # complete, or no start point
        return out
    k0 = int(todo[0])
    first = out.branch[-1]
    n = first.z.size
    root_n = np.sqrt(n)

    def fun_x(x, jac):
        r, J, trivial, n_core, payload = fun(x[:-1], x[-1], jac)
        Jx = np.hstack([J, dfun_ds(x[:-1], x[-1])[:, None]]) if jac else None
        return r, Jx, trivial, n_core, payload

    def rescale(x, _previous=None):
        """Arc-length scaling at ``x`` (the previous scaling is not needed)."""
        return np.r_[root_n * scale(x[:-1]), 1.0]

    nxt = [k0]
    prev = [np.r_[first.z, first.s]]
    why = [""]

    def on_grid(x, payload):
        """Accepted arc-length point: record it, then solve the grid values it passed."""
        if accept is not None:
            accept(x[:-1], payload)
        if x is prev[0]:                                  # the start point, already recorded
            return
        out.branch.append(ContinuationPoint(x[-1], x[:-1], payload, 0))
        xa = prev[0]
        while nxt[0] < grid.size and xa[-1] < grid[nxt[0]] <= x[-1]:
            k, sk = nxt[0], grid[nxt[0]]
            w = (sk - xa[-1]) / (x[-1] - xa[-1])
            guess = (1 - w) * xa[:-1] + w * x[:-1]
            res = newton(lambda zz, jj: fun(zz, sk, jj), guess, scale, tol, max_iter)
            sc = scale(guess)
            near = _moved(res.z, guess, sc, jump_mask) <= max(
                _moved(x[:-1], xa[:-1], sc, jump_mask), steps.jump_floor)
            if not (res.converged and near):
                why[0] = (f"re-solve at grid s={sk:.6g}: "
                          + (res.reason if not res.converged else "jumped off the branch"))
                nxt[0] = grid.size                           # stop; statuses set below
                break
            _record(out, k, sk, res, None)
            nxt[0] += 1
        prev[0] = x

    x0 = prev[0]
    direction = np.zeros(n + 1)
    direction[-1] = 1.0
    run = arclength(fun_x, x0, direction, rescale(x0), steps, tol, max_iter,
                    stop=lambda x: nxt[0] >= grid.size, max_points=max_points,
                    rescale=rescale, accept=on_grid, on_failure=on_failure,
                    jump_mask=None if jump_mask is None else np.r_[jump_mask, True])
    unfilled = [j for j in range(k0, grid.size) if out.points[j] is None]
    for j in unfilled:
        out.status[j] = Status.NO_CONVERGENCE if j == unfilled[0] else Status.NOT_REACHED
        out.reason[j] = (why[0] or f"arc length from s={first.s:.6g}: {run.reason}"
                         if j == unfilled[0] else "continuation stopped")
    return out
