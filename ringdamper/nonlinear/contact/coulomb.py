"""Isotropic Coulomb slider of the 3-D contact element (law ``"coulomb"``): its periodic state over one
period of the AFT and the derivatives of that state (docs/nonlinear_core.md §2).

The slider ``w`` (2-D) is dragged by a disc of radius ``r_k = μ N_k / kt`` whose centre is the tangential
relative displacement ``c_k = (d_t1, d_t2)(t_k)``. Between samples the centre moves on the straight
segment ``c_{k−1} → c_k`` and the slider is swept exactly (:class:`_Segment`): ``w_k = Φ_k(w_{k−1})``.
The periodic state solves the cyclic system ``W_k = Φ_k(W_{k−1})``, ``k = 0..Nt−1``, ``W_{−1} = W_{Nt−1}``:

* a pair that sticks over the whole period from its memory ``m`` (``|m − c_{k−1}| ≤ r_k`` and
  ``|m − c_k| ≤ r_k`` for every ``k``: the slider is inside the disc at both ends of every segment,
  hence along it) keeps ``W = m``;
* the others: Newton on the whole trajectory at once, vectorised over pairs and samples. The
  correction solves the linearised cyclic recurrence ``δ_k = A_k δ_{k−1} − R_k`` (``A_k = ∂Φ_k/∂w``,
  2 × 2; ``R_k = W_k − Φ_k(W_{k−1})``) by a two-level scan of the affine maps and one 2 × 2
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

Newton and the implicit function theorem take the step map's partial derivatives in closed form
(:class:`_Segment`); the march carries forward-mode derivatives (:class:`_Dual`) through
:func:`tractrix_step`, the same sweep written once more, operation by operation: it is the reference
the tests hold the closed form to. Inside Newton and the derivative, trajectories are laid out
``(2, Nt, n)`` (component, sample, pair: the 2 × 2 products broadcast over contiguous rows of pairs).
On the default ring's backbone states (``make bench``, ``coulomb``) a stuck state takes 0.2 ms, a
slipping one 5–6 ms (about 60 % Newton, 30 % the derivatives), 24.5× less than the march over the
backbone.
"""
from __future__ import annotations

import numpy as np

from ringdamper.nonlinear.contact.play import play_operator

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
    c, rm = np.ascontiguousarray(d[moving].transpose(1, 2, 0)), np.ascontiguousarray(r[moving].T)
    guess = play_operator(d[moving] - r[moving, None], d[moving] + r[moving, None], memory[moving], False)[0]
    Wm, ok, neutral = _newton_trajectory(c, rm, np.ascontiguousarray(guess.transpose(1, 2, 0)), scale, tol)
    stationary = np.max(np.abs(Wm - np.roll(Wm, 1, axis=1)), axis=(0, 1)) <= tol * scale
    neutral |= ok & stationary
    ok &= ~stationary
    solved = moving[ok]
    W[solved] = Wm[..., ok].transpose(2, 0, 1)
    if solved.size:
        derivative, unique = _trajectory_derivative(rate[solved], E, c[..., ok], Wm[..., ok], rm[:, ok],
                                                    closed[solved].T, jacobian)
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


class _Segment:
    """The step map ``Φ_k`` of every pair and sample and its partial derivatives in closed form.
    Arguments ``(2, …)`` (``r`` ``(…)``): the slider before the step ``w``, the disc's centre at both
    ends ``c_{k−1}``, ``c_k``, and its radius ``r_k``.

    In the frame of the motion, ``e = (c_k − c_{k−1}) / L``, ``ν`` = ``e`` turned by +90°: the slider
    projected on the disc ``z = (w − c_{k−1}) min(1, r / |w − c_{k−1}|)``, ``p = z·e``, ``q = z·ν``. The
    disc's edge reaches it after a travel ``s1 = p + √(r² − q²)``; when ``s1 < L`` it is dragged the
    remaining ``L − s1`` on a tractrix, ``tan(ψ/2) = T = q a``, ``a = e^{−(L−s1)/r} / (r + √(r² − q²))``,
    and ``Φ = c_k + r u``, ``u = −cos ψ e + sin ψ ν``. Otherwise it sticks, ``Φ = c_{k−1} + z``; with ``r = 0``,
    ``Φ = c_k``. Differentiating the slip, with ``u⊥ = ∂u/∂ψ = sin ψ e + cos ψ ν`` and
    ``dθ = ν·(dc_k − dc_{k−1}) / L`` the turn of ``e``: ``dΦ = dc_k + u dr + r u⊥ (dψ − dθ)``,
    ``dψ = 2 dT / (1 + T²)``, ``dT = (a √(r² − q²) dq + T (dp − dL)) / r + T (L − s1) dr / r²`` (the
    derivative of the root cancels out), ``dp = e·dz + q dθ``, ``dq = ν·dz − p dθ``.
    A translation of ``w``, ``c_{k−1}`` and ``c_k`` together translates ``Φ``:
    ``∂Φ/∂c_{k−1} = I − ∂Φ/∂w − ∂Φ/∂c_k``."""

    def __init__(self, w, prev, cur, r):
        self.prev, self.cur, self.r = prev, cur, r
        z = w - prev
        rho = np.sqrt(z[0] * z[0] + z[1] * z[1])
        shrink = rho > r
        rho = np.where(shrink, rho, 1.0)
        self.radial = z * (shrink / rho)                        # ẑ = ∂z/∂r where projected, else 0
        self.fac = np.where(shrink, r / rho, 1.0)
        self.z = z = z * self.fac
        step = cur - prev
        L = np.sqrt(step[0] * step[0] + step[1] * step[1])
        self.Ls = np.where(L > 0, L, 1.0)
        self.e = e = step / self.Ls
        self.nu = nu = np.stack([-e[1], e[0]])
        self.p, self.q = p, q = z[0] * e[0] + z[1] * e[1], z[1] * e[0] - z[0] * e[1]
        self.root = root = np.sqrt(np.maximum(r * r - q * q, 0.0))
        self.slip = (L > 0) & (p + root < L) & (r > 0)
        self.sep = r == 0
        self.rs = rs = np.where(self.slip, r, 1.0)
        self.rest = rest = np.where(self.slip, L - p - root, 0.0)   # travel in slip, L − s1
        self.a = np.exp(-rest / rs) / (rs + root)
        self.T = T = q * self.a
        self.kappa = kappa = 2.0 / (1.0 + T * T)                     # dψ/dT
        cos, sin = kappa - 1.0, kappa * T
        self.u, self.uperp = sin * nu - cos * e, sin * e + cos * nu

    def value(self):
        """``Φ_k(w)`` ``(2, …)``."""
        return np.where(self.sep, self.cur, np.where(self.slip, self.cur + self.rs * self.u, self.prev + self.z))

    def d_w(self):
        """``∂Φ/∂w`` ``(2, 2, …)``: ``u⊥ (r ∂ψ/∂z)ᵀ M`` in slip, ``M = ∂z/∂w`` when stuck, 0 at ``r = 0``."""
        h = self._r_dpsi_dz()
        along = self.radial[0] * h[0] + self.radial[1] * h[1]
        slip = self.uperp[:, None] * (self.fac * (h - along * self.radial))[None]          # u⊥ (M h)ᵀ
        stuck = self.fac * ~self.sep * (self._eye() - self.radial[:, None] * self.radial[None])
        return np.where(self.slip, slip, stuck)

    def d_cur(self):
        """``∂Φ/∂c_k`` ``(2, 2, …)``: ``I + u⊥ (r ∂(ψ − θ)/∂c_k)ᵀ`` in slip, 0 when stuck, ``I`` at ``r = 0``."""
        turn = (self.kappa * (self.T * self.q - self.a * self.root * self.p) - self.r) / self.Ls
        g = turn * self.nu - self.kappa * self.T * self.e                         # r ∂(ψ − θ)/∂c_k
        eye = self._eye()
        return np.where(self.sep, eye, np.where(self.slip, eye + self.uperp[:, None] * g[None], 0.0))

    def d_r(self):
        """``∂Φ/∂r`` ``(2, …)``: ``u + u⊥ r ∂ψ/∂r`` in slip, ``∂z/∂r`` when stuck, 0 at ``r = 0``."""
        h = self._r_dpsi_dz()
        dpsi = h[0] * self.radial[0] + h[1] * self.radial[1] + self.kappa * self.T * self.rest / self.rs
        return np.where(self.sep, 0.0, np.where(self.slip, self.u + self.uperp * dpsi, self.radial))

    def partials(self):
        """``∂Φ/∂w``, ``∂Φ/∂c_k``, ``∂Φ/∂r``."""
        return self.d_w(), self.d_cur(), self.d_r()

    def _r_dpsi_dz(self):
        """``r ∂ψ/∂z = 2 (T e + a √(r² − q²) ν) / (1 + T²)``."""
        return self.kappa * (self.T * self.e + self.a * self.root * self.nu)

    def _eye(self):
        """``I`` ``(2, 2, 1, …)``, broadcasting over the samples and pairs."""
        return np.eye(2).reshape((2, 2) + (1,) * self.r.ndim)


def _newton_trajectory(c, r, guess, scale, tol):
    """Newton on the cyclic trajectory (module docstring) from ``guess`` ``(2, Nt, n)`` (``c`` the same,
    ``r`` ``(Nt, n)``): the periodic trajectories of the pairs that converged (the others' are
    meaningless), which converged and which met a singular periodicity matrix on the way. A pair leaves
    the iteration when it converges or meets a singular matrix."""
    W, periodic = guess.copy(), guess.copy()
    prev = np.roll(c, 1, axis=1)
    ok, neutral = np.zeros(c.shape[2], bool), np.zeros(c.shape[2], bool)
    pairs = np.arange(c.shape[2])                                # the pairs iterated: columns of W, c, r
    for iteration in range(NEWTON_ITERATIONS + 1):
        step = _Segment(np.roll(W, 1, axis=1), prev, c, r)
        R = W - step.value()
        done = np.max(np.abs(R), axis=(0, 1)) <= tol * scale
        periodic[..., pairs[done]] = W[..., done]
        ok[pairs[done]] = True
        if done.all() or iteration == NEWTON_ITERATIONS:
            break
        delta, unique = cyclic_affine(step.d_w(), -R[:, :, None])
        W += delta[:, :, 0]
        neutral[pairs[~unique & ~done]] = True
        keep = unique & ~done
        if not keep.all():
            W, prev, c, r, pairs = W[..., keep], prev[..., keep], c[..., keep], r[:, keep], pairs[keep]
    return periodic, ok, neutral


def _trajectory_derivative(rate, E, c, W, r, closed, jacobian=True):
    """``∂W/∂c`` ``(n, 2, Nt, 3C)`` at the periodic trajectories ``W`` ``(2, Nt, n)`` (``c`` the same;
    ``r``, ``closed`` ``(Nt, n)``) by the implicit function theorem (module docstring; None without
    ``jacobian``), and which pairs have a unique orbit (non-singular periodicity matrix: without
    ``jacobian`` only that, from ``∂Φ/∂w`` alone)."""
    _, nt, n = c.shape
    before = np.roll(W, 1, axis=1), np.roll(c, 1, axis=1)
    if not jacobian:
        return None, cyclic_affine(_Segment(*before, c, r).d_w(), np.zeros((2, nt, 1, n)))[1]
    A, cur, radius = _Segment(*before, c, r).partials()
    dW, unique = cyclic_affine(A, _right_hand_sides(A, cur, radius * (rate * closed), E))
    return dW.transpose(3, 0, 1, 2), unique


def _right_hand_sides(A, cur, normal, E):
    """Right-hand sides ``(2, Nt, 3C, n)`` of ``∂W/∂c`` from the partials ``A_k = ∂Φ_k/∂w``,
    ``∂Φ_k/∂c_k`` and ``∂Φ_k/∂d_n = ∂Φ_k/∂r ∂r_k/∂d_n`` (``normal``): ``∂Φ_k/∂d_n E_k`` for the normal
    coefficients and, with ``∂Φ/∂c_{k−1} = I − A_k − ∂Φ/∂c_k``, ``(I − A_k) E_{k−1} + ∂Φ_k/∂c_k
    (E_k − E_{k−1})`` for the tangential ones."""
    nt, C = E.shape
    rest = np.eye(2)[:, :, None, None] - A
    before = np.roll(E, 1, axis=0)[:, :, None]
    G = np.empty((2, nt, 3, C, A.shape[-1]))
    np.multiply(normal[:, :, None], E[:, :, None], out=G[:, :, 0])
    for j in range(2):
        np.multiply(cur[:, j, :, None], E[:, :, None] - before, out=G[:, :, 1 + j])
        G[:, :, 1 + j] += rest[:, j, :, None] * before
    return G.reshape(2, nt, 3 * C, -1)


def cyclic_affine(A: np.ndarray, b: np.ndarray):
    """Solution of ``x_k = A_k x_{k−1} + b_k``, ``k = 0..Nt−1``, ``x_{−1} = x_{Nt−1}``, for every pair:
    ``A`` ``(2, 2, Nt, n)``, ``b`` ``(2, Nt, m, n)`` (overwritten by ``x`` when contiguous). A two-level
    scan: the samples in blocks (:func:`_block_size`), each block's prefix compositions
    ``x_k = P_k x_s + q_k`` from its start ``x_s`` sample after sample (vectorised over blocks and
    pairs), the blocks composed one after the other, ``(I − P) x_{−1} = q`` for the whole period, then
    every block's start and its samples. Written out elementwise (:func:`_times`): batched ``matmul``
    on 2 × 2 blocks costs ten times more. Returns ``x`` ``(2, Nt, m, n)`` and which pairs have
    ``|det(I − P)| > SINGULAR`` (elsewhere ``x`` is meaningless)."""
    _, _, nt, n = A.shape
    m = b.shape[2]
    size = _block_size(nt)
    blocks = nt // size
    P = A.transpose(0, 2, 1, 3).copy().reshape(2, blocks, size, 2, n)  # rows, blocks, samples, columns
    q = b.reshape(2, blocks, size, m, n)
    scratch = np.empty((2, blocks, m, n))
    for j in range(1, size):
        _add_times(q[:, :, j], P[:, :, j], q[:, :, j - 1], scratch)
        P[:, :, j] = _times(P[:, :, j], P[:, :, j - 1])
    through_P, through_q = P[:, :, -1].copy(), q[:, :, -1].copy()      # period's start → each block's end
    for k in range(1, blocks):
        through_q[:, k] += _times(through_P[:, k], through_q[:, k - 1])
        through_P[:, k] = _times(through_P[:, k], through_P[:, k - 1])
    start, unique = _periodic_start(through_P[:, -1], through_q[:, -1])
    starts = np.concatenate([start[:, None], _times(through_P[:, :-1], start[:, None]) + through_q[:, :-1]],
                            axis=1)
    for j in range(size):
        _add_times(q[:, :, j], P[:, :, j], starts, scratch)
    return q.reshape(2, nt, m, n), unique


def _block_size(nt):
    """Samples per block of :func:`cyclic_affine`: the largest divisor of ``Nt`` up to ``⌈√Nt⌉`` (as many
    sequential steps within the blocks as across them)."""
    return max(k for k in range(1, int(np.ceil(np.sqrt(nt))) + 1) if nt % k == 0)


def _periodic_start(P, q):
    """``x = (I − P)⁻¹ q`` for ``P`` ``(2, 2, n)``, ``q`` ``(2, m, n)`` (2 × 2 adjugate), and where
    ``|det(I − P)| > SINGULAR``."""
    I_P = np.eye(2)[:, :, None] - P
    det = I_P[0, 0] * I_P[1, 1] - I_P[0, 1] * I_P[1, 0]
    unique = np.abs(det) > SINGULAR
    inverse = np.array([[I_P[1, 1], -I_P[0, 1]], [-I_P[1, 0], I_P[0, 0]]]) / np.where(unique, det, 1.0)
    return _times(inverse, q), unique


def _add_times(out, A, B, scratch):
    """``out += A @ B`` as :func:`_times`, through ``scratch`` (the shape of ``out``) instead of temporaries."""
    for k in range(2):
        np.multiply(A[..., k:k + 1, :], B[k], out=scratch)
        out += scratch


def _times(A, B):
    """``A @ B`` for 2 × 2 ``A`` ``(2, …, 2, n)`` and ``B`` ``(2, …, m, n)``: rows on the first axis,
    columns on the one before the pairs ``n`` (the axes between broadcast)."""
    return A[..., 0:1, :] * B[0] + A[..., 1:2, :] * B[1]


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


