"""Isotropic Coulomb slider of the 3-D contact element (law ``"coulomb"``): its periodic state over one
period of the AFT and the derivatives of that state (docs/nonlinear_core.md §2).

The slider ``w`` (2-D) is dragged by a disc of radius ``r_k = μ N_k / kt`` whose centre is the tangential
relative displacement ``c_k = (d_t1, d_t2)(t_k)``. Between samples the centre moves on the straight
segment ``c_{k−1} → c_k`` and the slider is swept exactly (:func:`tractrix_step`): ``w_k = Φ_k(w_{k−1})``.
The periodic state solves the cyclic system ``W_k = Φ_k(W_{k−1})``, ``k = 0..Nt−1``, ``W_{−1} = W_{Nt−1}``:

* a pair that sticks over the whole period from its memory ``m`` (``|m − c_{k−1}| ≤ r_k`` and
  ``|m − c_k| ≤ r_k`` for every ``k``: the slider is inside the disc at both ends of every segment,
  hence along it) keeps ``W = m``;
* the others: Newton on the whole trajectory at once, vectorised over pairs and samples. The
  correction solves the linearised cyclic recurrence ``δ_k = A_k δ_{k−1} − R_k`` (``A_k = ∂Φ_k/∂w``,
  2 × 2; ``R_k = W_k − Φ_k(W_{k−1})``) by a parallel prefix scan of the affine maps and one 2 × 2
  periodicity solve per pair (:func:`cyclic_affine`). Start: the play operator of each direction alone
  (the square ``|w_j − c_j| ≤ r`` for the disc). Converged when ``max|R| ≤ tol · (max|c| + max r)``;
* the derivatives at the periodic state by the implicit function theorem: the same recurrence, with
  the right-hand sides ``∂Φ_k/∂(c_{k−1}, c_k, r_k)`` taken to the harmonic coefficients;
* a pair whose Newton does not converge in :data:`NEWTON_ITERATIONS` is marched period after period
  from its memory, with forward-mode derivatives, until the state at the period start and its
  derivatives repeat to ``tol`` (:func:`march`, the former method for every pair);
* a pair whose Newton solution does not move over the period, or whose periodicity matrix
  ``I − A_{Nt−1}⋯A_0`` is singular, has no unique orbit: every position that sticks over the whole
  period is periodic (Newton lands on one of them, often on the edge of that set, where ``A`` is that of
  a slip), or the product has an eigenvalue 1 (the slider only pushed radially by a shrinking disc,
  its angle neutral). Its orbit is the one reached from the memory: marched until the state repeats,
  with the derivatives of that march (along a neutral direction they grow period after period, so
  they are not required to settle).

The step map's derivatives are forward-mode (:class:`_Dual`) through the tractrix formulas.
"""
from __future__ import annotations

import numpy as np

from ringdamper.nonlinear.play import play_operator

#: Newton iterations on a trajectory before its pair is marched instead
NEWTON_ITERATIONS = 30

#: ``|det(I − A_{Nt−1}⋯A_0)|`` below which the periodic orbit counts as not unique (marched instead)
SINGULAR = 1e-12


def coulomb_slider(rate, E, d, r, closed, jacobian, memory, tol=1e-13, max_periods=500):
    """Periodic slider positions ``W`` ``(np, 2, Nt)`` for the tangential displacements ``d``
    ``(np, 2, Nt)`` and radii ``r`` ``(np, Nt)``, and (``jacobian``) ``∂W/∂c`` ``(np, 2, Nt, 3C)`` with
    respect to the coefficients ``c`` of ``[d_n, d_t1, d_t2]`` on the basis ``E`` (Nt × C).
    ``rate`` ``(np,)``: ``∂r/∂d_n = μ kn / kt`` where ``closed`` ``(np, Nt)``. ``memory`` ``(np, 2)``:
    the slider before the period. Module docstring for the method."""
    npairs, _, nt = d.shape
    C = E.shape[1]
    scale = np.max(np.abs(d)) + np.max(r) + np.finfo(float).tiny
    W = np.repeat(np.asarray(memory, float)[:, :, None], nt, axis=2)
    dW = np.zeros((npairs, 2, nt, 3 * C)) if jacobian else None
    moving = np.flatnonzero(~_stuck_throughout(d, r, memory))
    if not moving.size:
        return W, dW
    guess = np.stack([play_operator(d[moving, j] - r[moving], d[moving, j] + r[moving],
                                    memory[moving, j])[0] for j in range(2)], axis=1)
    Wm, ok, neutral = _newton_trajectory(d[moving], r[moving], guess, scale, tol)
    stationary = np.max(np.abs(Wm - np.roll(Wm, 1, axis=2)), axis=(1, 2)) <= tol * scale
    neutral |= ok & stationary
    ok &= ~stationary
    solved = moving[ok]
    W[solved] = Wm[ok]
    if solved.size:
        derivative, unique = _trajectory_derivative(rate[solved], E, d[solved], W[solved], r[solved],
                                                    closed[solved], jacobian)
        if jacobian:
            dW[solved] = derivative
        neutral[np.flatnonzero(ok)[~unique]] = True
        ok[np.flatnonzero(ok)[~unique]] = False
    for settle, pairs in ((True, moving[~ok & ~neutral]), (False, moving[neutral])):
        if pairs.size:
            W[pairs], dWm = march(rate[pairs], E, d[pairs], r[pairs], closed[pairs], jacobian, memory[pairs],
                                  scale, tol, max_periods, settle)
            if jacobian:
                dW[pairs] = dWm
    return W, dW


def _stuck_throughout(d, r, memory):
    """Pairs whose slider stays at its memory over the whole period (module docstring)."""
    m = np.asarray(memory, float)[:, :, None]
    here, before = m - d, m - np.roll(d, 1, axis=2)
    inside = ((np.hypot(here[:, 0], here[:, 1]) <= r) & (np.hypot(before[:, 0], before[:, 1]) <= r)
              & (r > 0))
    return inside.all(axis=1)


def _step_map(w, prev, cur, r, seeds):
    """``Φ_k(w)`` for every pair and sample (arrays ``(n, 2, Nt)``; ``r`` ``(n, Nt)``) and its
    derivatives along ``seeds``: the inputs (0, 1: w; 2, 3: c_{k−1}; 4, 5: c_k; 6: r_k) differentiated,
    in this order. Returns the values ``(n, 2, Nt)`` and the derivatives ``(n, Nt, 2, len(seeds))``."""
    n, _, nt = w.shape
    flat = [x.reshape(-1) for x in (w[:, 0], w[:, 1], prev[:, 0], prev[:, 1], cur[:, 0], cur[:, 1], r)]
    eye = np.eye(len(seeds))
    duals = [_Dual(v, np.broadcast_to(eye[seeds.index(i)], (v.size, len(seeds))) if i in seeds else None)
             for i, v in enumerate(flat)]
    out = tractrix_step((duals[0], duals[1]), (duals[2], duals[3], None), (duals[4], duals[5], duals[6]))
    values = np.stack([o.v.reshape(n, nt) for o in out], axis=1)
    deriv = np.stack([(o.t if o.t is not None else np.zeros((n * nt, len(seeds)))).reshape(n, nt, -1)
                      for o in out], axis=2)
    return values, deriv


def _newton_trajectory(c, r, guess, scale, tol):
    """Newton on the cyclic trajectory (module docstring) from ``guess`` ``(n, 2, Nt)``: the periodic
    trajectories, which pairs converged and which met a singular periodicity matrix on the way."""
    W = guess.copy()
    prev = np.roll(c, 1, axis=2)
    ok, neutral = np.zeros(c.shape[0], bool), np.zeros(c.shape[0], bool)
    todo = np.arange(c.shape[0])
    for _ in range(NEWTON_ITERATIONS + 1):
        if not todo.size:
            break
        phi, A = _step_map(np.roll(W[todo], 1, axis=2), prev[todo], c[todo], r[todo], [0, 1])
        R = W[todo] - phi
        done = np.max(np.abs(R), axis=(1, 2)) <= tol * scale
        ok[todo[done]] = True
        todo, R, A = todo[~done], R[~done], A[~done]
        if not todo.size:
            break
        delta, unique = cyclic_affine(A, -R.transpose(0, 2, 1)[..., None])
        W[todo[unique]] += delta[unique, ..., 0].transpose(0, 2, 1)
        neutral[todo[~unique]] = True
        todo = todo[unique]
    return W, ok, neutral


def _trajectory_derivative(rate, E, d, W, r, closed, jacobian=True):
    """``∂W/∂c`` ``(n, 2, Nt, 3C)`` at the periodic trajectories ``W`` by the implicit function theorem
    (module docstring; None without ``jacobian``), and which pairs have a unique orbit (non-singular
    periodicity matrix: without ``jacobian`` only that, from ``∂Φ/∂w`` alone)."""
    n, _, nt = d.shape
    C = E.shape[1]
    _, D = _step_map(np.roll(W, 1, axis=2), np.roll(d, 1, axis=2), d, r, list(range(7) if jacobian else range(2)))
    if not jacobian:
        return None, cyclic_affine(D, np.zeros((n, nt, 2, 1)))[1]
    E_prev = np.roll(E, 1, axis=0)
    G = np.zeros((n, nt, 2, 3 * C))
    G[..., :C] = (D[..., 6] * (rate[:, None] * closed)[..., None])[..., None] * E[None, :, None, :]
    for j in range(2):
        block = slice((j + 1) * C, (j + 2) * C)
        G[..., block] = D[..., 2 + j, None] * E_prev[None, :, None, :] + D[..., 4 + j, None] * E[None, :, None, :]
    dW, unique = cyclic_affine(D[..., :2], G)
    return dW.transpose(0, 2, 1, 3), unique


def cyclic_affine(A: np.ndarray, b: np.ndarray):
    """Solution of ``x_k = A_k x_{k−1} + b_k``, ``k = 0..Nt−1``, ``x_{−1} = x_{Nt−1}``, for every pair:
    ``A`` ``(n, Nt, 2, 2)``, ``b`` ``(n, Nt, 2, m)``. The prefix compositions ``x_k = P_k x_{−1} + q_k``
    by a Hillis–Steele scan (log₂ Nt levels of 2 × 2 products, written out elementwise: batched
    ``matmul`` on 2 × 2 blocks costs ten times more), then ``(I − P_{Nt−1}) x_{−1} = q_{Nt−1}``.
    Returns ``x`` and which pairs have ``|det(I − P_{Nt−1})| > SINGULAR`` (elsewhere ``x`` is
    meaningless)."""
    P, q = A.copy(), b.copy()
    nt = A.shape[1]
    step = 1
    while step < nt:
        P[:, step:], q[:, step:] = _times(P[:, step:], P[:, :-step]), _times(P[:, step:], q[:, :-step]) + q[:, step:]
        step *= 2
    I_P = np.eye(2) - P[:, -1]
    det = I_P[:, 0, 0] * I_P[:, 1, 1] - I_P[:, 0, 1] * I_P[:, 1, 0]
    unique = np.abs(det) > SINGULAR
    inverse = np.stack([np.stack([I_P[:, 1, 1], -I_P[:, 0, 1]], -1),
                        np.stack([-I_P[:, 1, 0], I_P[:, 0, 0]], -1)], -2) / np.where(unique, det, 1.0)[:, None, None]
    start = _times(inverse, q[:, -1])
    return _times(P, start[:, None]) + q, unique


def _times(A, B):
    """``A @ B`` for stacks of 2 × 2 ``A`` and 2 × m ``B`` (broadcast over the leading axes)."""
    return np.stack([A[..., 0, :1] * B[..., 0, :] + A[..., 0, 1:] * B[..., 1, :],
                     A[..., 1, :1] * B[..., 0, :] + A[..., 1, 1:] * B[..., 1, :]], axis=-2)


def march(rate, E, d, r, closed, jacobian, memory, scale, tol, max_periods, settle_derivatives=True):
    """Slider positions and (``jacobian``) their derivatives as :func:`coulomb_slider` returns them,
    marched period after period from ``memory`` until the state at the period start repeats to ``tol``
    (relative to ``scale``; derivatives carried along in forward mode, :class:`_Dual`), and with
    ``settle_derivatives`` its derivatives too (not for an orbit that is not unique: along its neutral
    direction they grow period after period)."""
    npairs, _, nt = d.shape
    C = E.shape[1]
    zero = np.zeros((npairs, 3 * C)) if jacobian else None

    def signal(k):                                       # d_t1, d_t2 and r at sample k, with tangents
        if not jacobian:
            return _Dual(d[:, 0, k]), _Dual(d[:, 1, k]), _Dual(r[:, k])
        t1, t2, tr = zero.copy(), zero.copy(), zero.copy()
        t1[:, C:2 * C] = E[k]
        t2[:, 2 * C:] = E[k]
        tr[:, :C] = (rate * closed[:, k])[:, None] * E[k]
        return _Dual(d[:, 0, k], t1), _Dual(d[:, 1, k], t2), _Dual(r[:, k], tr)

    samples = [signal(k) for k in range(nt)]
    w = (_Dual(memory[:, 0].astype(float), zero), _Dual(memory[:, 1].astype(float), zero))
    prev = samples[-1]
    W = np.empty((npairs, 2, nt))
    dW = np.empty((npairs, 2, nt, 3 * C)) if jacobian else None
    for _ in range(max_periods):
        start = w
        for k in range(nt):
            w = tractrix_step(w, prev, samples[k])
            prev = samples[k]
            W[:, 0, k], W[:, 1, k] = w[0].v, w[1].v
            if jacobian:
                dW[:, 0, k], dW[:, 1, k] = w[0].t, w[1].t
        change = max(np.max(np.abs(w[i].v - start[i].v)) for i in range(2)) / scale
        if jacobian and settle_derivatives:
            change = max(change, max(np.max(np.abs(w[i].t - start[i].t)) for i in range(2))
                         / (1.0 + np.max(np.abs(dW))))
        if change <= tol:
            break
    else:
        raise RuntimeError(f"Coulomb hysteresis not periodic after {max_periods} periods")
    return W, dW


def tractrix_step(w, prev, cur):
    """Exact sweeping of the slider ``w`` by the disc of radius ``r_k`` whose centre moves on the
    straight segment ``d_{k−1} → d_k``: projection on the shrunk disc, stick until the disc edge
    reaches the slider (travel ``s1``), then a tractrix ``tan(ψ/2) = tan(ψ1/2) e^{−(s−s1)/r}``."""
    (cx0, cy0, _), (cx1, cy1, r) = prev, cur
    zx, zy = w[0] - cx0, w[1] - cy0
    rho = _sqrt(zx * zx + zy * zy)
    shrink = rho.v > r.v
    fac = _where(shrink, r / _where(shrink, rho, 1.0), 1.0)
    zx, zy = zx * fac, zy * fac
    dx, dy = cx1 - cx0, cy1 - cy0
    L = _sqrt(dx * dx + dy * dy)
    moving = L.v > 0
    Ls = _where(moving, L, 1.0)
    ex, ey = dx / Ls, dy / Ls
    p = zx * ex + zy * ey
    px, py = zx - p * ex, zy - p * ey                    # part of z normal to the motion
    root = _sqrt(_maximum0(r * r - px * px - py * py))
    s1 = p + root
    slip = moving & (s1.v < L.v) & (r.v > 0)
    rs = _where(slip, r, 1.0)
    decay = (-(L - s1) / rs).exp()
    t_over = decay / _where(slip, rs + root, 1.0)       # tan(ψ/2) / |p_perp|
    t2 = t_over * t_over * (px * px + py * py)
    cos_psi = (1.0 - t2) / (1.0 + t2)
    lateral = 2.0 * rs * t_over / (1.0 + t2)
    sx = cx1 - rs * cos_psi * ex + lateral * px
    sy = cy1 - rs * cos_psi * ey + lateral * py
    sep = r.v == 0
    wx = _where(sep, cx1, _where(slip, sx, cx0 + zx))
    wy = _where(sep, cy1, _where(slip, sy, cy0 + zy))
    return wx, wy


class _Dual:
    """Value ``v`` ``(n,)`` with forward-mode tangent ``t`` ``(n, nvar)`` (None: values only)."""

    __slots__ = ("v", "t")

    def __init__(self, v, t=None):
        self.v, self.t = v, t

    def _lift(self, o):
        return o if isinstance(o, _Dual) else _Dual(np.broadcast_to(o, self.v.shape), None)

    def __add__(self, o):
        o = self._lift(o)
        return _Dual(self.v + o.v, _addt(self.t, o.t))

    __radd__ = __add__

    def __neg__(self):
        return _Dual(-self.v, None if self.t is None else -self.t)

    def __sub__(self, o):
        return self + (-self._lift(o))

    def __rsub__(self, o):
        return (-self) + o

    def __mul__(self, o):
        o = self._lift(o)
        return _Dual(self.v * o.v, _addt(_scale(self.t, o.v), _scale(o.t, self.v)))

    __rmul__ = __mul__

    def __truediv__(self, o):
        o = self._lift(o)
        q = self.v / o.v
        return _Dual(q, _addt(_scale(self.t, 1.0 / o.v), _scale(o.t, -q / o.v)))

    def __rtruediv__(self, o):
        return self._lift(o) / self

    def exp(self):
        e = np.exp(self.v)
        return _Dual(e, _scale(self.t, e))


def _addt(a, b):
    if a is None:
        return b
    return a if b is None else a + b


def _scale(t, s):
    return None if t is None else t * s[:, None]


def _sqrt(x):
    s = np.sqrt(x.v)
    return _Dual(s, _scale(x.t, 0.5 / np.where(s > 0, s, np.inf)))


def _maximum0(x):
    pos = x.v > 0
    return _Dual(np.where(pos, x.v, 0.0), _scale(x.t, pos.astype(float)))


def _where(mask, a, b):
    a = a if isinstance(a, _Dual) else _Dual(np.broadcast_to(float(a), mask.shape))
    b = b if isinstance(b, _Dual) else _Dual(np.broadcast_to(float(b), mask.shape))
    if a.t is None and b.t is None:
        t = None
    else:
        ta = a.t if a.t is not None else 0.0
        tb = b.t if b.t is not None else 0.0
        t = np.where(mask[:, None], ta, tb)
    return _Dual(np.where(mask, a.v, b.v), t)


