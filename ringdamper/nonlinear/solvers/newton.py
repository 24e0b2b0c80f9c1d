"""Newton–Raphson on dense Jacobians with exact elimination of trivial unknowns.

The condensed HBM Jacobian (:mod:`ringdamper.nonlinear.harmonic_balance.condensed`) has unit-vector columns for the
contact coordinates of pairs whose contact Jacobian vanishes (open during the whole period, or
decoupled): such an unknown appears only in its own row (identity) and possibly in the extra
rows appended by the problem (normalisation, phase, arc-length). :class:`Factorization`
eliminates them exactly before the LU factorisation, so the dense solve only involves the
active pairs.

A problem may give its Jacobian as an operator (:mod:`ringdamper.nonlinear.solvers.jacobian`): Newton forms
it when it factorises, and the continuation's tangents solve with it by GMRES on a lagged
factorisation (:func:`linear_solver`, :mod:`ringdamper.nonlinear.solvers.krylov`). Newton's own steps always
use an LU: its chord steps with the factorisation it was given (a lagged solver's LU), a fresh
Jacobian factorised. Measured on the default ring (H = 3, n ≈ 1480; docs/nonlinear_core.md §10):
GMRES Newton steps on a lagged LU, or chord steps by GMRES, cost more than they save (a pair that
changes its stick/slip state changes the Jacobian by a block of rank up to 3(2H + 1), which GMRES
on the old LU needs as many iterations to capture), whereas the tangents need 3–7 iterations.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable

import numpy as np
import scipy.linalg as sla
from scipy.linalg.lapack import dgecon, dlange, get_lapack_funcs

from ringdamper.nonlinear.solvers import krylov
from ringdamper.nonlinear.solvers.budget import charge_lu
from ringdamper.nonlinear.solvers.jacobian import dense, is_operator
from ringdamper.nonlinear.solvers.krylov import LaggedSolver


class Factorization:
    """LU of ``J`` after eliminating the trivial unknowns ``T`` (columns ``e_i`` in the first
    ``n_core`` rows): ``x_T = b_T − J[T, N] x_N`` and the Schur system on the other unknowns.
    ``overwrite``: ``J`` is a temporary the LU may overwrite (no copy of the matrix).

    ``scale`` (the unknowns' convergence scales): the Schur matrix ``A`` is factorised equilibrated,
    ``D_r A D_c`` with ``D_c = diag(scale)`` and ``D_r`` one over each row's largest entry of
    ``A D_c``, and :meth:`condition` estimates κ₁ of that matrix
    (:mod:`ringdamper.nonlinear.indicators.conditioning`); the solves are those of ``A``."""

    def __init__(self, J: np.ndarray, trivial: np.ndarray | None, n_core: int, overwrite: bool = False,
                 scale: np.ndarray | None = None):
        charge_lu()                                          # an open LU budget may stop the work here
        n = self.n = J.shape[0]
        T = np.zeros(n, bool) if trivial is None else np.r_[trivial, np.zeros(n - trivial.size, bool)]
        self.T, self.N = np.flatnonzero(T), np.flatnonzero(~T)
        extra = self.N[self.N >= n_core]                     # rows that may touch T columns
        self.JTN = J[np.ix_(self.T, self.N)]
        self.JXT = J[np.ix_(extra, self.T)]
        self.extra_pos = np.searchsorted(self.N, extra)
        A = J.T[np.ix_(self.N, self.N)].T if self.T.size else J        # Fortran order: LU in place
        if self.T.size and extra.size:
            A[self.extra_pos] -= self.JXT @ self.JTN
        self.rows = self.columns = None
        if scale is not None:
            A = A if overwrite or A is not J else A.copy(order="F")
            self.columns = np.asarray(scale, float)[self.N]
            self.rows, self.norm = _equilibrate(A, self.columns)
        self.lu = sla.lu_factor(A, check_finite=False, overwrite_a=overwrite or A is not J)
        self._getrs, = get_lapack_funcs(("getrs",), (self.lu[0],))

    @property
    def factorization(self) -> "Factorization":
        """Itself (the LU a :class:`ringdamper.nonlinear.solvers.krylov.LaggedSolver` stands on otherwise)."""
        return self

    def solve(self, b: np.ndarray) -> np.ndarray:
        bN = b[self.N].copy()
        if self.T.size and self.extra_pos.size:
            bN[self.extra_pos] -= self.JXT @ b[self.T]
        if self.rows is not None:
            bN *= self.rows
        x = np.empty_like(b)
        xN = self._lu_solve(bN)
        x[self.N] = xN if self.columns is None else xN * self.columns
        x[self.T] = b[self.T] - self.JTN @ x[self.N]
        return x

    def _lu_solve(self, b: np.ndarray) -> np.ndarray:
        """``A⁻¹ b`` from the LU, overwriting ``b``: LAPACK's ``getrs``, what ``scipy.linalg.lu_solve``
        calls, without its checks and batching layer (about 6 µs a solve, more than ``getrs`` itself on the
        small systems whose Newton iterations are mostly such overhead)."""
        if not b.size:
            return b
        x, info = self._getrs(*self.lu, b, overwrite_b=True)
        if info:
            raise ValueError(f"getrs: illegal value in argument {-info}")
        return x

    def condition(self) -> float:
        """κ₁ of the equilibrated matrix (LAPACK's ``dgecon`` estimate from the LU, Higham's 1-norm
        estimator); ``inf`` if it is singular or has a zero or non-finite row. Needs ``scale``."""
        if self.rows is None:
            raise ValueError("condition: the factorisation was not equilibrated (pass scale)")
        if not np.isfinite(self.norm):
            return np.inf
        rcond, info = dgecon(self.lu[0], self.norm, norm="1")
        return 1.0 / rcond if info == 0 and rcond > 0 else np.inf


def _equilibrate(A: np.ndarray, scale: np.ndarray) -> tuple[np.ndarray, float]:
    """Scale ``A`` in place to ``D_r A D_c`` (``D_c = diag(scale)``, ``D_r``: one over each row's
    largest entry of ``A D_c``); returns the diagonal of ``D_r`` and the 1-norm of the result
    (``inf`` where a row vanishes or is not finite: that row is left unscaled)."""
    A *= scale
    top = np.maximum(np.max(A, axis=1), -np.min(A, axis=1))       # max |A_ij| without a temporary
    bad = ~(np.isfinite(top) & (top > 0))
    rows = 1.0 / np.where(bad, 1.0, top)
    A *= rows[:, None]
    return rows, np.inf if np.any(bad) else float(dlange("1", A))


def factorize(J, trivial: np.ndarray | None, n_core: int):
    """The :class:`Factorization` of ``J`` (a matrix, or an operator formed for the occasion, whose
    matrix the LU may then overwrite), or the smaller system an operator offers for it
    (``J.reduced_solver(order)``, given the order of the full LU; None: it offers none)."""
    offer = getattr(J, "reduced_solver", None) if is_operator(J) else None
    if offer is not None:
        solver = offer(J.shape[0] - (0 if trivial is None else int(np.count_nonzero(trivial))))
        if solver is not None:
            return solver
    return Factorization(dense(J), trivial, n_core, overwrite=is_operator(J))


def linear_solver(J, trivial: np.ndarray | None, n_core: int, previous=None,
                  weights: np.ndarray | None = None, rtol: float = krylov.RTOL):
    """Solver of systems with the Jacobian ``J``: GMRES preconditioned by the LU of ``previous``
    (a solver of an earlier Jacobian of the same shape) when ``J`` is an operator of at least
    :data:`ringdamper.nonlinear.solvers.krylov.MIN_SIZE` unknowns
    (:class:`ringdamper.nonlinear.solvers.krylov.LaggedSolver`;
    ``weights``: 1/scale of the unknowns; ``rtol``: the GMRES accuracy), otherwise the
    :class:`Factorization` of ``J``."""
    lagged = is_operator(J) and J.shape[0] >= krylov.MIN_SIZE
    if lagged and previous is not None and previous.factorization.n == J.shape[0]:
        return LaggedSolver(J, previous.factorization, weights,    # A: the operator J formed anew
                            lambda A: Factorization(A, trivial, n_core, overwrite=True), rtol=rtol)
    return factorize(J, trivial, n_core)


@dataclass(frozen=True)
class StepRule:
    """How long the steps on one factorisation go on: while they contract at a rate
    ``θ < theta_max`` and the iterations still needed at that rate stay within ``chord_budget``."""

    theta_max: float
    chord_budget: int


#: chord steps: a rate of 1/2 and a dozen more steps (a chord step costs a residual, a fresh
#: Jacobian some 20: docs/nonlinear_core.md §10)
CHORD = StepRule(theta_max=0.5, chord_budget=12)

#: quasi-Newton steps: they converge superlinearly once on their way, so they are followed up to a
#: first rate of 0.7 and the budget only bounds runaway cases (measured on campaign rings against
#: 0.5 and 0.8: docs/nonlinear_core.md §10)
QUASI_NEWTON = StepRule(theta_max=0.7, chord_budget=100)


#: with ``give_up_damping``: a Newton correction (at a fresh Jacobian) more than this many times the one at
#: the previous fresh Jacobian ends the run unconverged (:func:`newton`). 1 cut six top points of a
#: campaign ring and a chain of the randomised family; 2 keeps them (docs/nonlinear_core.md §4.1)
GROWTH_LIMIT = 2.0


@dataclass
class NewtonResult:
    z: np.ndarray
    converged: bool
    iterations: int
    payload: Any                      # the problem's evaluation at ``z``
    factorization: Factorization | LaggedSolver | None   # the solver last used
    reason: str = ""
    jacobians: int = 0                # fresh Jacobians (factorised, or solved with a lagged LU)
    effort: float = 0.0               # Jacobians + iterations / chord budget


def newton(fun: Callable, z0: np.ndarray, scale: Callable[[np.ndarray], np.ndarray],
           tol: float = 1e-10, max_iter: int = 20, factorization: Factorization | None = None,
           theta_max: float | None = None, chord_budget: int | None = None,
           lambda_min: float = 1.0 / 256, give_up_damping: float | None = None,
           quasi_newton: bool = False) -> NewtonResult:
    """Newton's method with Jacobian reuse and damping for ``r(z) = 0``.

    ``fun(z, jacobian) -> Evaluation`` (:class:`ringdamper.nonlinear.solvers.jacobian.Evaluation`; ``J`` None
    when not requested).
    Converged when the step ``δz`` computed at ``z`` satisfies ``max |δz| / scale(z) ≤ tol``; ``z``
    and its evaluation are returned (outputs are consistent with ``z``), with the factorisation
    last used (a tangent predictor may reuse it).

    Steps (after Deuflhard, *Newton Methods for Nonlinear Problems*, 2004):

    * chord steps with the given (or last) factorisation while they contract (rate
      θ < ``theta_max``) and the iterations still needed at that rate stay within
      ``chord_budget`` (a chord step costs a residual, far less than a Jacobian and its LU);
      otherwise the Jacobian is recomputed at the better point. With ``quasi_newton``, the
      steps on that factorisation are good Broyden steps instead (:class:`QuasiNewtonSteps`,
      superlinear where the chord steps contract linearly), and the defaults follow their
      contraction further (:data:`QUASI_NEWTON`; :data:`CHORD` otherwise);
    * after a fresh Jacobian, a damped step ``λ δz``: accepted when the simplified correction
      ``J⁻¹ r(z + λδz)`` is shorter than ``(1 − λ/4) |δz|`` (natural monotonicity test), else λ
      is halved down to ``lambda_min``. This breaks the cycles plain Newton falls into on the
      piecewise-linear AFT residual near stick–slip transitions.
    * ``give_up_damping``: the first damped step that needs ``λ ≤ give_up_damping`` ends the run
      unconverged (Deuflhard's failure criterion, at a raised floor). For the predictor–corrector
      steps, which halve the step on failure: a Newton direction that passes the monotonicity test
      only for so short a step means that the predictor lies outside the corrector's region of
      contraction (mostly across a kink of the piecewise-linear AFT residual, where the damped
      iterations creep and cycle between contact states); a halved step, whose predictor lies
      closer, is cheaper than creeping on (docs/nonlinear_core.md §4.1). With it, a Newton correction
      more than :data:`GROWTH_LIMIT` times the one at the previous fresh Jacobian ends the run too:
      the damped steps accepted in between crossed a kink into a region where the linearisation
      points further away than from where they started, the cycling between contact states that
      would otherwise spend the corrector's whole budget of Jacobians.

    ``max_iter`` bounds the Newton (fresh Jacobian) iterations; all iterations together are
    bounded by ``4 max_iter``. The decisions depend only on the iterates (no timing), so runs
    are reproducible. ``effort`` = Jacobians + iterations / ``chord_budget``.
    """
    defaults = QUASI_NEWTON if quasi_newton else CHORD
    theta_max = defaults.theta_max if theta_max is None else theta_max
    chord_budget = defaults.chord_budget if chord_budget is None else chord_budget
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        res = _iterate(fun, np.array(z0, float), scale, tol, max_iter, factorization,
                       theta_max, chord_budget, lambda_min, give_up_damping, quasi_newton)
    res.effort = res.jacobians + res.iterations / chord_budget
    return res


def _iterate(fun, z, scale, tol, max_iter, fac, theta_max, chord_budget, lambda_min, give_up,
             quasi_newton):
    n_jac = n_newton = it = 0
    floor = lambda_min if give_up is None else max(lambda_min, give_up)   # the run ends at give_up
    fresh = fac is None
    fac = None if fresh else fac.factorization       # chord steps with an LU
    ev = fun(z, fresh)
    dz = None                                    # correction of ``ev`` with ``fac``, if known
    steps = None                                 # quasi-Newton steps taken on ``fac``
    last_newton = np.inf                         # the Newton correction at the last fresh Jacobian
    while True:
        if fresh:
            if ev.J is None:
                ev = fun(z, True)
            if not (np.all(np.isfinite(ev.r)) and (is_operator(ev.J) or np.all(np.isfinite(ev.J)))):
                return NewtonResult(z, False, it, ev.payload, None, "non-finite residual or Jacobian",
                                    n_jac)
            fac = factorize(ev.J, ev.trivial, ev.n_core)
            n_jac += 1
            dz = steps = None
        payload = ev.payload
        if dz is None:
            dz = _correction(fac, ev.r)
        sc = scale(z)
        if quasi_newton and steps is None:
            steps = QuasiNewtonSteps(sc**-2.0)       # the scaled Euclidean product
        step = np.max(np.abs(dz) / sc)
        if not np.isfinite(step):
            if fresh:
                return NewtonResult(z, False, it, payload, fac, "singular Jacobian", n_jac)
            fresh = True
            continue
        if step <= tol:
            return NewtonResult(z, True, it, payload, fac, "", n_jac)
        if fresh and give_up is not None:
            if step > GROWTH_LIMIT * last_newton:
                return NewtonResult(z, False, it, payload, fac,
                                    f"Newton correction grew from {last_newton:.3g} to {step:.3g} between Jacobians",
                                    n_jac)
            last_newton = step
        if n_newton >= max_iter or it >= 4 * max_iter:
            break
        it += 1
        if fresh:                                    # damped Newton step
            n_newton += 1
            lam = 1.0
            while True:
                trial = fun(z + lam * dz, False)
                corr = _correction(fac, trial.r)
                bar = np.max(np.abs(corr) / sc)
                if bar <= (1.0 - lam / 4) * step or lam <= floor:
                    break
                lam *= 0.5
            if give_up is not None and lam <= give_up:
                return NewtonResult(z, False, it, payload, fac,
                                    f"damped step of {lam:g} <= {give_up:g} (outside Newton's contraction)", n_jac)
            if steps is not None and lam == 1.0:     # a full step: the first secant on ``fac``
                steps.take(dz)
                corr = steps.correction(corr)[0]
            z, ev, dz, fresh = z + lam * dz, trial, corr, lam < 1.0
            continue
        trial = fun(z + dz, False)                   # chord (or quasi-Newton) step on ``fac``
        corr = contracted = _correction(fac, trial.r)
        if steps is not None:
            corr, contracted = steps.correction(corr, dz)
        theta = np.max(np.abs(contracted) / sc) / step
        if theta < theta_max:
            needed = np.log(tol / (theta * step)) / np.log(theta) if theta > 0 else 0.0
            if needed <= chord_budget:
                if steps is not None:
                    steps.take(dz)
                z, ev, dz = z + dz, trial, corr
                continue
        if theta < 1:
            z, ev = z + dz, trial
        fresh = True
    return NewtonResult(z, False, it, payload, fac, f"no convergence in {it} iterations", n_jac)


def _correction(fac, r):
    return fac.solve(-r) if np.all(np.isfinite(r)) else np.full(r.size, np.inf)


class QuasiNewtonSteps:
    """Good Broyden updates of a factorised Jacobian ``J₀``, applied to its corrections
    (Deuflhard's error-oriented quasi-Newton method QNERR, *Newton Methods for Nonlinear
    Problems*, 2004, §2.1.4). With the steps ``Δx₀ … Δx_k`` taken since ``J₀`` (each the
    quasi-Newton correction at its start), the correction at ``x_{k+1}`` is

    ``v = −J₀⁻¹ F(x_{k+1})``, ``v ← v + ⟨Δx_{i−1}, v⟩/‖Δx_{i−1}‖² · Δx_i`` for i = 1 … k,
    ``Δx_{k+1} = v / (1 − ⟨Δx_k, v⟩/‖Δx_k‖²)``,

    which is ``−J_{k+1}⁻¹ F(x_{k+1})`` for the Broyden matrices ``J_{i+1} = J_i + F(x_{i+1})
    Δx_iᵀ W / ‖Δx_i‖²`` (the secant condition along the step taken, the rank-one change smallest
    in the inner product ``⟨a, b⟩ = aᵀ W b``, ``W = diag(weights)``). Each step costs one solve
    with ``J₀`` and ``k`` inner products; where the chord method contracts linearly, by the rate
    ``θ`` at which ``J₀`` misses ``J``, these steps converge superlinearly."""

    def __init__(self, weights: np.ndarray):
        self.weights = weights
        self.taken: list[tuple[np.ndarray, np.ndarray, float]] = []   # Δx, W Δx, ‖Δx‖²

    def take(self, dz: np.ndarray) -> None:
        """Record the step ``dz`` (the correction this object returned, or ``J₀``'s own)."""
        self.taken.append(self._entry(dz))

    def _entry(self, dz):
        wdz = self.weights * dz
        return dz, wdz, float(wdz @ dz)

    def correction(self, v: np.ndarray,
                   pending: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
        """The quasi-Newton correction from ``J₀``'s correction ``v`` at the point reached by the
        steps taken and ``pending`` (the step that led there, not yet recorded), and ``v`` before
        the last division (its length over the last step's is the contraction rate θ)."""
        history = self.taken if pending is None else self.taken + [self._entry(pending)]
        if not history:
            return v, v
        for (_, wa, aa), (b, _, _) in zip(history[:-1], history[1:]):
            v = v + (wa @ v / aa) * b
        _, wa, aa = history[-1]
        return v / (1.0 - wa @ v / aa), v
