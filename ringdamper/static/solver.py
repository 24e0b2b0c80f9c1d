"""Nonlinear static equilibrium with unilateral normal contact (paper §2.4, §3.1.2; docs/design.md §3.2).

Problem. A linear elastic structure (stiffness ``K``, symmetric positive semi-definite, already
constrained and spin-softened by the caller) under a load ``f`` touches itself through ``m``
contact pairs. ``G`` (3m × n, pair-major rows ``3p, 3p+1, 3p+2``) maps the DoFs to the relative
displacements ``d = (d_n, d_t1, d_t2)`` of each pair in its local frame, ``d = u_ring − u_blisk``,
``d_n > 0`` closing. With the generalised contact forces ``λ = (N, T1, T2)`` per pair::

    K u + Gᵀ λ = f,        g = g0 − d_n,        T = kt · d_t                      (1)

and one of two normal laws:

* ``method="penalty"`` (default, the law of the dynamic contact element)::

      N = kn · max(d_n − g0, 0)                                                  (2)

* ``method="lagrange"`` (exact unilateral contact)::

      N ≥ 0,   g ≥ 0,   N · g = 0     ⇔     min(N, s·g) = 0   (any s > 0)       (3)

Method. Because everything but the normal law is linear, the problem is condensed exactly onto
the ``m`` normal contact coordinates. A regularised matrix in which every pair is *closed*,

    A0 = K + Gnᵀ S Gn + Gtᵀ diag(kt) Gt,          S = diag(s) > 0               (4)

is factorised once (sparse LU). It is regular whenever the structure is restrained with all
contacts closed, even when ``K`` is singular (a ring held only by contact). Writing the contact
forces as ``λ = S d + μ`` on the normal rows (the tangential springs are exactly inside ``A0``)::

    u = A0⁻¹ (f − Gnᵀ μ),     d_n = a − F μ,     a = Gn A0⁻¹ f,   F = Gn A0⁻¹ Gnᵀ   (5)

so the unknown is ``μ`` (m values) and ``F`` (m × m, dense, symmetric) is the only coupling. The
equilibrium residual of (1) is ``r = Gnᵀ ρ`` with ``ρ = N(d_n) − S d_n − μ``; it is the quantity
tested for convergence (‖r‖₂ ≤ tol·‖f‖₂, absolute when f = 0, or below the round-off floor of
its terms), never an iteration count. The residual of (1) is recomputed with ``K`` at the end.

* Penalty: semi-smooth Newton on ``ρ(μ) = 0`` with ``s = kn``, started with the pairs that the
  all-closed solution pushes towards closing (a > 0) closed at their gap. ``ρ`` is the
  (negative, preconditioned) gradient of the convex potential energy restricted to the affine
  set (5), so an exact line search on that piecewise-quadratic energy makes the iteration
  globally convergent. When the open pairs leave
  a mechanism (singular Newton matrix) they get a tiny stiffness ε·kn in the Newton matrix only:
  the step then moves the free rigid mode until a pair touches; a full step along such a
  direction means the load pulls a body away from every contact (no equilibrium: status 1).
* Lagrange: primal–dual active set = semi-smooth Newton on ``min(N, s·g) = 0`` (Hintermüller, Ito
  & Kunisch 2002), started from the penalty solution with ``kn = s``; if an active set repeats
  (cycling), the Newton matrix is singular or the iteration budget is spent, it falls back to the
  augmented Lagrangian (Uzawa) iteration ``N ← max(N + s(d_n − g0), 0)`` whose inner problems are
  penalty problems with the shifted gap ``g0 − N/s``.

Every physics failure returns a result with ``status ≠ 0`` and a ``reason`` (never an exception);
wrong argument shapes raise ``ValueError`` naming the argument. See ``docs/static_contact.md``.
"""
from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp

from ringdamper.fem.superlu import SymmetricLU

CONVERGED = 0
NOT_CONVERGED = 1
INVALID_INPUT = 2
SINGULAR = 3
STATUS_NAMES = {CONVERGED: "converged", NOT_CONVERGED: "not converged",
                INVALID_INPUT: "invalid physical input", SINGULAR: "singular system"}

METHODS = ("penalty", "lagrange")
FORWARD_ERROR_TOL = 1e-2  # A0 is singular when a solve with a known answer is worse than this
RCOND_TOL = 1e-13  # smallest accepted reciprocal condition number of a dense Newton matrix
ACCURACY_TOL = 1e-6  # a "converged" solution whose residual with K exceeds this is rejected
ROUNDOFF = 1e3 * np.finfo(float).eps  # relative round-off floor of a contact-space residual
STALL_ITER = 3  # full exact Newton steps in an unchanged active set before giving up
MECHANISM_EPS = 1e-6  # relative stiffness given to open pairs when they leave a mechanism


@dataclass
class StaticContactResult:
    """Static contact state. Arrays are per pair (m,) unless stated; SI units.

    ``u`` (n,) displacements; ``N0`` normal force ≥ 0; ``gap`` = max(g0 − d_n, 0) on open pairs
    and exactly 0 on active ones (exact complementarity: ``N0 · gap`` is 0 to the bit);
    ``penetration`` = max(d_n − g0, 0) (the penalty interpenetration, ~0 for Lagrange);
    ``in_contact`` = N0 > 0; ``tangential`` (m, 2) = kt·(d_t1, d_t2);
    ``relative_displacement`` (m, 3) = (d_n, d_t1, d_t2); ``iterations`` Newton/active-set
    iterations (all stages); ``residual`` = ‖K u + Gᵀλ − f‖₂/‖f‖₂ (absolute if f = 0), computed
    with ``K`` itself; ``complementarity`` = max|N0·max(g0 − d_n, 0)| / (max N0 · max(|g0|,
    |d_n|, |u|)) before the projection onto exact complementarity (a KKT residual: round-off
    for a converged solve);
    ``status`` 0 = converged, 1 = not converged, 2 = invalid physical input, 3 = singular system;
    ``reason`` human-readable.
    """

    u: np.ndarray
    N0: np.ndarray
    gap: np.ndarray
    penetration: np.ndarray
    in_contact: np.ndarray
    tangential: np.ndarray
    relative_displacement: np.ndarray
    iterations: int
    residual: float
    complementarity: float
    status: int
    reason: str
    method: str

    @property
    def converged(self) -> bool:
        return self.status == CONVERGED


@dataclass
class _Outcome:
    """What an iteration returns: the unknown μ, the iterations spent, status and reason."""

    mu: np.ndarray
    iterations: int
    status: int = CONVERGED
    reason: str = "converged"


# ----------------------------------------------------------------------------- arguments
def _per_pair(value, m, name):
    """Broadcast a scalar or an (m,) array to a float (m,) array; ValueError on a wrong shape."""
    arr = np.asarray(value, dtype=float)
    if arr.ndim == 0:
        return np.full(m, float(arr))
    if arr.shape != (m,):
        raise ValueError(f"{name} must be a scalar or have shape ({m},), got {arr.shape}")
    return arr.copy()


def _check_shapes(K, f, G, g0, kn, kt, method):
    """Validate and convert the arguments (shapes only; values are checked by _physics_problem)."""
    if method not in METHODS:
        raise ValueError(f"method must be one of {METHODS}, got {method!r}")
    if not sp.issparse(K) or K.ndim != 2 or K.shape[0] != K.shape[1]:
        raise ValueError(f"K must be a square scipy.sparse matrix, got {type(K).__name__} "
                         f"of shape {getattr(K, 'shape', None)}")
    n = K.shape[0]
    f = np.asarray(f, dtype=float)
    if f.shape != (n,):
        raise ValueError(f"f must have shape ({n},) to match K, got {f.shape}")
    g0 = np.asarray(g0, dtype=float)
    if g0.ndim != 1:
        raise ValueError(f"g0 must be a 1-D array (one gap per pair), got shape {g0.shape}")
    m = g0.size
    if not sp.issparse(G) or G.shape != (3 * m, n):
        raise ValueError(f"G must be a scipy.sparse matrix of shape (3m, n) = ({3 * m}, {n}), "
                         f"got {type(G).__name__} of shape {getattr(G, 'shape', None)}")
    if kn is None and method == "penalty":
        raise ValueError("kn is required by method='penalty'")
    kn = None if kn is None else _per_pair(kn, m, "kn")
    kt = _per_pair(kt, m, "kt")
    return sp.csc_matrix(K, dtype=float), f, sp.csr_matrix(G, dtype=float), g0, kn, kt


def _first(mask, count=10):
    """The first ``count`` indices where ``mask`` holds (for messages)."""
    return np.flatnonzero(mask)[:count].tolist()


def _physics_problem(K, f, G, g0, kn, kt):
    """Reason why the data cannot describe a physical problem, or None if they can."""
    for name, values in (("K", K.data), ("f", f), ("G", G.data), ("g0", g0), ("kt", kt)):
        if not np.all(np.isfinite(values)):
            return f"non-finite entries in {name}"
    if kn is not None and not np.all(np.isfinite(kn) & (kn > 0)):
        return f"normal stiffness kn must be finite and > 0 (pairs {_first(~(kn > 0))})"
    if np.any(kt < 0):
        return f"tangential stiffness kt must be >= 0 (pairs {_first(kt < 0)})"
    scale = abs(K).max() if K.nnz else 0.0
    if scale > 0 and abs(K - K.T).max() > 1e-10 * scale:
        return "K is not symmetric"
    return None


def _default_scale(K, Gn):
    """Per-pair stiffness scale s_p = n_pᵀ K n_p (local stiffness seen by pair p)."""
    s = np.asarray((Gn @ K).multiply(Gn).sum(axis=1)).ravel()
    positive = s[s > 0]
    return np.where(s > 0, s, positive.max() if positive.size else 1.0)


# ----------------------------------------------------------------------- condensed space
class _ContactSpace:
    """Exact condensation (5) of the structure onto the normal contact coordinates."""

    def __init__(self, K, f, G, s, kt):
        self.Gn, Gt = G[0::3], sp.vstack([G[1::3], G[2::3]]).tocsr()
        A0 = (K + self.Gn.T @ self.Gn.multiply(s[:, None])
              + Gt.T @ Gt.multiply(np.tile(kt, 2)[:, None])).tocsc()
        # SuperLU's own solves: the supernodal copy of the factors would double the memory held
        self.lu = SymmetricLU(A0, definite=True)
        # One solve with a known answer z rides along with the m columns A0⁻¹ Gnᵀ.
        z = np.random.default_rng(0).standard_normal(A0.shape[0])
        X = self.lu.solve(np.column_stack([self.Gn.T.toarray(), A0 @ z, f]))
        self.forward_error = float(np.linalg.norm(X[:, -2] - z) / np.linalg.norm(z))
        F = self.Gn @ X[:, :-2]
        self.F = 0.5 * (F + F.T)
        self.u_f = X[:, -1]
        self.a = self.Gn @ self.u_f

    @property
    def singular(self):
        """A0 is (numerically) singular: the known-answer solve lost all accuracy."""
        return not self.forward_error <= FORWARD_ERROR_TOL

    def start(self, g0, s):
        """Initial μ: pairs that the all-closed solution ``a`` pushes towards closing (a > 0)
        start closed at their gap (μ = −s·g0), the others open at ``a`` (μ = −s·a), so that a
        pressed ring starts restrained and f = 0 starts (and ends) at u = 0 exactly."""
        return -s * np.where(self.a > 0, g0, self.a)

    def normal_displacement(self, mu):
        """d_n = a − F μ, eq. (5)."""
        return self.a - self.F @ mu

    def displacement(self, mu):
        """u = A0⁻¹ (f − Gnᵀ μ), eq. (5)."""
        return self.u_f - self.lu.solve(self.Gn.T @ mu)

    def force_norm(self, rho):
        """‖Gnᵀ ρ‖₂: the nodal force residual of (1) for the contact-space residual ρ."""
        return float(np.linalg.norm(self.Gn.T @ rho))

    def tolerance(self, tol_abs, *terms):
        """max(tol_abs, round-off floor): a residual summed from ``terms`` cannot be resolved
        below ROUNDOFF·‖Gnᵀ Σ|term|‖ (this makes f = 0 with g0 ≠ 0 and very stiff s converge)."""
        return max(tol_abs, ROUNDOFF * self.force_norm(sum(np.abs(t) for t in terms)))


def _solve_dense(A, b):
    """Solve A x = b, or return None when A is numerically singular (LAPACK rcond estimate)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", sla.LinAlgWarning)
        lu, piv = sla.lu_factor(A, check_finite=False)
    rcond, _ = sla.lapack.dgecon(lu, np.linalg.norm(A, 1), norm="1")
    if not rcond > RCOND_TOL:
        return None
    return sla.lu_solve((lu, piv), b, check_finite=False)


# --------------------------------------------------------------------------- penalty law
def _penalty_residual(d, mu, g, kn):
    """ρ = kn·max(d − g, 0) − kn·d − μ: contact-space residual of (1) under the law (2), s = kn."""
    return np.where(d > g, -kn * g, -kn * d) - mu


def _exact_line_search(d, dd, mu, dmu, g, kn):
    """Minimiser in (0, 1] of the convex energy along μ + tΔμ (slope Δdᵀρ(t), piecewise linear).

    Returns 1 when the energy still decreases at the full step, else the root of the slope
    located between consecutive kinks (where d + t·Δd crosses g) and interpolated exactly.
    """
    def slope(t):
        return dd @ _penalty_residual(d + t * dd, mu + t * dmu, g, kn)

    if slope(1.0) <= 0.0:
        return 1.0
    with np.errstate(divide="ignore", invalid="ignore"):
        kinks = (g - d) / dd
    kinks = np.unique(kinks[(kinks > 0) & (kinks < 1)])
    ts = np.concatenate(([0.0], kinks, [1.0]))
    slopes = np.array([slope(t) for t in ts])
    j = int(np.argmax(slopes > 0))  # first point where the slope turns positive (j ≥ 1)
    t0, t1, s0, s1 = ts[j - 1], ts[j], slopes[j - 1], slopes[j]
    return float(t0 + (t1 - t0) * (-s0) / (s1 - s0))


def _newton_direction(F, kn, closed, rho):
    """Solve (I + (J − S)F) Δμ = ρ with J = kn on closed pairs, else 0 (exact Newton).

    If the open pairs leave a mechanism (singular matrix), they get the stiffness ε·kn
    (ε = MECHANISM_EPS) instead: the step then moves the free rigid mode until a pair touches
    (the line search stops at that kink). Last resort: the all-closed direction Δμ = ρ. Every
    returned direction descends the energy (Δdᵀρ < 0). Returns (Δμ, exact Newton step?).
    """
    open_kn = np.where(closed, 0.0, kn)
    for eps in (0.0, MECHANISM_EPS):
        dmu = _solve_dense(np.eye(len(rho)) - ((1.0 - eps) * open_kn)[:, None] * F, rho)
        if dmu is not None and (F @ dmu) @ rho > 0.0:
            return dmu, eps == 0.0
    return rho, False


def _penalty_newton(space, g, kn, mu, tol_abs, max_iter):
    """Globalised semi-smooth Newton for ρ(μ) = 0 with the penalty law (2) (s must equal kn).

    In exact arithmetic a full exact Newton step that keeps the active set lands on the
    solution; if that happens STALL_ITER times in a row without meeting the tolerance, the
    tolerance is below the round-off floor and the iteration stops (status 1).
    """
    F, repeats, previous = space.F, 0, None
    for it in range(max_iter + 1):
        d = space.normal_displacement(mu)
        rho = _penalty_residual(d, mu, g, kn)
        if not np.all(np.isfinite(rho)):
            return _Outcome(mu, it, NOT_CONVERGED, "non-finite residual in the penalty iteration")
        residual = space.force_norm(rho)
        if residual <= space.tolerance(tol_abs, kn * np.maximum(d - g, 0.0), kn * d, mu):
            return _Outcome(mu, it)
        closed = d > g
        repeats = repeats + 1 if previous is not None and np.array_equal(closed, previous) else 0
        if repeats >= STALL_ITER:
            return _Outcome(mu, it, NOT_CONVERGED, f"stalled at residual {residual:.2e} > "
                            f"{tol_abs:.2e} (round-off floor: loosen tol)")
        if it == max_iter:
            break
        dmu, exact = _newton_direction(F, kn, closed, rho)
        dd = -F @ dmu
        if dd @ rho >= 0.0:
            return _Outcome(mu, it, NOT_CONVERGED,
                            "penalty iteration stagnated: no descent direction")
        t = _exact_line_search(d, dd, mu, dmu, g, kn)
        if not exact and t == 1.0:  # a free rigid mode moved ~1/ε too far and touched nothing
            return _Outcome(mu, it + 1, NOT_CONVERGED, "no equilibrium: the load moves a body "
                            "away from every contact (unrestrained rigid-body mode)")
        previous = closed if exact and t == 1.0 else None
        mu = mu + t * dmu
    return _Outcome(mu, max_iter, NOT_CONVERGED,
                    f"penalty Newton did not converge in {max_iter} iterations")


# ------------------------------------------------------------------------- Lagrange law
def _ncp_residual(space, mu, g0, s):
    """min(N, s·g) with N = μ + s·d_n and g = g0 − d_n (eq. 3); zero iff (3) holds."""
    d = space.normal_displacement(mu)
    N, sg = mu + s * d, s * (g0 - d)
    return np.minimum(N, sg), sg < N


def _ncp_converged(space, phi, mu, g0, s, tol_abs):
    """‖Gnᵀ min(N, s·g)‖ within the tolerance (or the round-off floor of its terms)."""
    d = space.normal_displacement(mu)
    return space.force_norm(phi) <= space.tolerance(tol_abs, mu, s * d, s * g0)


def _active_set(space, g0, s, mu, tol_abs, max_iter):
    """Primal–dual active set (semi-smooth Newton on min(N, s·g) = 0) with cycling detection."""
    F, eye, seen = space.F, np.eye(len(mu)), set()
    for it in range(max_iter + 1):
        phi, active = _ncp_residual(space, mu, g0, s)
        if _ncp_converged(space, phi, mu, g0, s, tol_abs):
            return _Outcome(mu, it)
        key = active.tobytes()
        if key in seen:
            return _Outcome(mu, it, NOT_CONVERGED, "active set cycling")
        seen.add(key)
        if it == max_iter:
            break
        sF = s[:, None] * F
        dmu = _solve_dense(np.where(active[:, None], sF, eye - sF), -phi)
        if dmu is None:
            return _Outcome(mu, it, NOT_CONVERGED, "singular active-set system (mechanism)")
        mu = mu + dmu
    return _Outcome(mu, max_iter, NOT_CONVERGED,
                    f"active-set iteration did not converge in {max_iter} iterations")


def _augmented_lagrangian(space, g0, s, mu, tol_abs, max_iter):
    """Uzawa iteration N ← max(N + s(d_n − g0), 0), each a penalty problem, gap g0 − N/s."""
    iterations = 0
    N = np.maximum(mu + s * space.normal_displacement(mu), 0.0)
    for _ in range(max_iter):
        inner = _penalty_newton(space, g0 - N / s, s, mu, tol_abs, max_iter)
        iterations += inner.iterations
        if inner.status != CONVERGED:
            return _Outcome(inner.mu, iterations, inner.status, inner.reason)
        mu = inner.mu
        phi, _ = _ncp_residual(space, mu, g0, s)
        if _ncp_converged(space, phi, mu, g0, s, tol_abs):
            return _Outcome(mu, iterations)
        N = np.maximum(mu + s * space.normal_displacement(mu), 0.0)
    return _Outcome(mu, iterations, NOT_CONVERGED,
                    f"augmented Lagrangian did not converge in {max_iter} outer iterations")


def _lagrange(space, g0, s, tol_abs, max_iter):
    """Exact contact (3): penalty start (kn = s), active-set Newton, augmented Lagrangian fallback.
    """
    start = _penalty_newton(space, g0, s, space.start(g0, s), tol_abs, max_iter)
    if start.status != CONVERGED:
        return start
    pdas = _active_set(space, g0, s, start.mu, tol_abs, max_iter)
    if pdas.status == CONVERGED:
        return _Outcome(pdas.mu, start.iterations + pdas.iterations)
    alm = _augmented_lagrangian(space, g0, s, pdas.mu, tol_abs, max_iter)
    alm.iterations += start.iterations + pdas.iterations
    if alm.status != CONVERGED:
        alm.reason = f"{pdas.reason}; fallback: {alm.reason}"
    return alm


# ----------------------------------------------------------------------------- driver
def _normal_force(space, mu, g0, s, method):
    """N from the law: (2) for penalty; Lagrange: μ + s·d_n on the active set, else 0."""
    d = space.normal_displacement(mu)
    if method == "penalty":
        return s * np.maximum(d - g0, 0.0)
    N = mu + s * d
    return np.where(s * (g0 - d) < N, np.maximum(N, 0.0), 0.0)


def _result(K, f, G, g0, kt, u, N, iterations, status, reason, method):
    """Assemble the result from u and N; the residual of (1) is recomputed with K itself."""
    d = (G @ u).reshape(-1, 3)
    T = kt[:, None] * d[:, 1:]
    lam = np.column_stack([N, T]).ravel()
    residual = float(np.linalg.norm(K @ u + G.T @ lam - f))
    f_norm = float(np.linalg.norm(f))
    raw_gap = np.maximum(g0 - d[:, 0], 0.0)
    n_ref = N.max() if N.size else 0.0
    # length scale of the problem: gaps, normal motions or displacements, whichever is largest
    g_ref = max(np.abs(g0).max(initial=0.0), np.abs(d[:, 0]).max(initial=0.0),
                np.abs(u).max(initial=0.0))
    comp = float(np.abs(N * raw_gap).max(initial=0.0) / (n_ref * g_ref)) if n_ref * g_ref > 0 else 0.0
    in_contact = N > 0
    # Exact complementarity by construction: the active set decides. An active pair's gap is 0
    # (the Lagrange law's g = 0 holds in d only to round-off, which depends on the BLAS/SIMD path
    # of G @ u; ``complementarity`` reports the size of what this projection removes); an open
    # pair's N0 is already exactly 0 by both laws.
    gap = np.where(in_contact, 0.0, raw_gap)
    return StaticContactResult(
        u=u, N0=N, gap=gap, penetration=np.maximum(d[:, 0] - g0, 0.0), in_contact=in_contact,
        tangential=T, relative_displacement=d, iterations=iterations,
        residual=residual / f_norm if f_norm > 0 else residual, complementarity=comp,
        status=status, reason=reason, method=method)


def _failure(K, f, G, g0, kt, status, reason, method, iterations=0):
    """A result carrying no solution (NaN fields) and the reason why."""
    m, n = g0.size, K.shape[0]
    nan = np.full(m, np.nan)
    return StaticContactResult(
        u=np.full(n, np.nan), N0=nan, gap=nan.copy(), penetration=nan.copy(),
        in_contact=np.zeros(m, bool), tangential=np.full((m, 2), np.nan),
        relative_displacement=np.full((m, 3), np.nan), iterations=iterations,
        residual=np.nan, complementarity=np.nan, status=status, reason=reason, method=method)


def solve_static_contact(K, f, G, g0, kn, kt, *, method="penalty", tol=1e-10,
                         max_iter=100) -> StaticContactResult:
    """Static equilibrium (1) with the penalty (2) or exact (3) normal law (module docstring).

    Parameters
    ----------
    K : scipy.sparse (n, n), symmetric positive semi-definite (singular directions must be
        restrained by the contact springs/constraints).
    f : (n,) external load.
    G : scipy.sparse (3m, n), rows 3p, 3p+1, 3p+2 give (d_n, d_t1, d_t2) of pair p, d_n > 0 closing.
    g0 : (m,) initial gaps; negative values are an initial interference (a ring pressed into its
        groove at rest): the penalty law (2) then loads the pair before any motion, the exact law
        (3) pushes the bodies apart until g = g0 − d_n ≥ 0.
    kn : scalar or (m,) normal penalty stiffness (N/m), > 0. Required for ``"penalty"``; for
        ``"lagrange"`` it is only the scale ``s`` of (4) and of the NCP, which does not change
        the solution (None: s = 100·n_pᵀ K n_p, a hundred times the local stiffness).
    kt : scalar or (m,) tangential sticking stiffness (N/m), ≥ 0, used by both methods.
    method : ``"penalty"`` or ``"lagrange"``.
    tol : convergence tolerance on ‖K u + Gᵀλ − f‖₂ / ‖f‖₂ (absolute when f = 0).
    max_iter : iteration guard of every Newton / active-set / augmented-Lagrangian loop.

    Returns a :class:`StaticContactResult`; physics failures give ``status ≠ 0`` and a reason
    (with NaN fields when there is no solution at all, else the last iterate).
    Raises ``ValueError`` only for ill-shaped arguments or an unknown method.
    """
    K, f, G, g0, kn, kt = _check_shapes(K, f, G, g0, kn, kt, method)
    problem = _physics_problem(K, f, G, g0, kn, kt)
    if problem is not None:
        return _failure(K, f, G, g0, kt, INVALID_INPUT, problem, method)
    s = kn if kn is not None else 100.0 * _default_scale(K, G[0::3])
    try:
        space = _ContactSpace(K, f, G, s, kt)
    except (RuntimeError, np.linalg.LinAlgError) as err:  # "Factor is exactly singular", a pivot <= 0
        return _failure(K, f, G, g0, kt, SINGULAR, f"structure not restrained with every contact "
                        f"closed (factorisation failed: {err})", method)
    if space.singular:
        return _failure(K, f, G, g0, kt, SINGULAR, "structure not restrained with every contact "
                        "closed (rigid-body mode: a body without enough contact or supports; "
                        f"known-answer solve error {space.forward_error:.1e})", method)
    tol_abs = tol * float(np.linalg.norm(f))
    if method == "penalty":
        out = _penalty_newton(space, g0, s, space.start(g0, s), tol_abs, max_iter)
    else:
        out = _lagrange(space, g0, s, tol_abs, max_iter)
    u = space.displacement(out.mu)
    N = _normal_force(space, out.mu, g0, s, method)
    if not (np.all(np.isfinite(u)) and np.all(np.isfinite(N))):
        return _failure(K, f, G, g0, kt, NOT_CONVERGED, f"non-finite solution ({out.reason})",
                        method, out.iterations)
    result = _result(K, f, G, g0, kt, u, N, out.iterations, out.status, out.reason, method)
    if result.status == CONVERGED and not result.residual <= ACCURACY_TOL:
        result.status = SINGULAR
        result.reason = (f"converged in the contact space but the residual with K is "
                         f"{result.residual:.1e} (ill-conditioned system)")
    return result
