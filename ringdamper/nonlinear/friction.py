"""3-D frictional contact element and its alternating frequency–time (AFT) evaluation.

Element (paper §2.5.2 after Yang & Menq 1998; docs/design.md §2 "Contact pairs"), per pair, in the local
frame (n, t1, t2) of the relative displacement d = u_ring − u_blisk (d_n > 0 closes the contact):

* normal: unilateral spring with preload ``N0`` or gap ``gap`` (one of them zero),
  ``N(t) = max(N0 + kn (d_n(t) − gap), 0)``;
* tangential, law ``"jenkins"`` (the paper's element): one Jenkins element per direction j = 1, 2,
  ``T_j = kt (d_j − w_j)``, slider ``w_j`` moving only when ``|T_j|`` would exceed ``μ N(t)``;
  when separated (N = 0) the slip limit is zero, so ``w_j = d_j``, ``T_j = 0`` and the memory is lost;
* tangential, law ``"coulomb"`` (isotropic option): one 2-D slider, ``|T| ≤ μ N(t)`` as a circle.

Time discretisation: the slider follows the *play operator* ``w_k = proj_{[d_k ± r_k]}(w_{k−1})``
with ``r_k = μ N_k / kt``, exact at the samples for inputs monotone between samples. The slider
memory before the period is an input, ``w = 0`` by default: the static equilibrium (zero tangential
force there, so stuck contacts behave as the linear springs ``(kn, kt, kt)`` of the linearised stuck
system). The harmonic balance passes that default at every evaluation, so a solution does not depend
on the continuation path (docs/nonlinear_core.md §2).

Periodic state ("march until periodic", docs/design.md §2): for the Jenkins law the map "one period" is a
clamp ``w ↦ clip(w, A, B)`` (a composition of clamps is a clamp), which is idempotent, so the state
reached after marching the first period from the memory is periodic; it is computed for all samples
at once by a parallel prefix scan of the clamps and the periodicity of the start state is checked.
For the Coulomb law the march is repeated period after period until the state at the period start
repeats to a tolerance.

Jacobian: exact chain rule through the marched hysteresis. For the Jenkins law every slider value
is either the initial memory or a bound ``d_s ∓ r_s`` of some earlier sample ``s`` (its *source*),
so ``∂w_k/∂c = ∂(d_s ∓ r_s)/∂c``. For the Coulomb law the derivative is propagated with the state.
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from ringdamper.fem.contact_law import spring_diagonal, stuck_springs
from ringdamper.nonlinear.fourier import Fourier

LAWS = ("jenkins", "coulomb")

#: per-pair parameters of :class:`FrictionContacts`
PARAMETERS = ("kn", "kt", "mu", "N0", "gap")


@dataclass(frozen=True)
class FrictionContacts:
    """Parameters of ``npairs`` contact pairs (arrays broadcast to shape ``(npairs,)``).

    ``kn``, ``kt`` [N/m] normal and tangential stiffness, ``mu`` friction coefficient, ``N0`` [N]
    normal preload, ``gap`` [m] initial gap (per pair at most one of ``N0``, ``gap`` is non-zero),
    ``law`` ``"jenkins"`` (paper) or ``"coulomb"`` (isotropic).
    """

    kn: np.ndarray
    kt: np.ndarray
    mu: np.ndarray
    N0: np.ndarray
    gap: np.ndarray
    law: str = "jenkins"

    def __post_init__(self):
        values = {k: np.atleast_1d(np.asarray(getattr(self, k), float)) for k in PARAMETERS}
        for k, a in values.items():
            if a.ndim != 1:
                raise ValueError(f"FrictionContacts.{k}: expected a scalar or a 1-D array (one value per "
                                 f"contact pair), got shape {np.shape(getattr(self, k))}")
        per_pair = {k: a.size for k, a in values.items() if a.size > 1}
        if len(set(per_pair.values())) > 1:
            raise ValueError("FrictionContacts: parameters given per pair disagree on the number of pairs: "
                             + ", ".join(f"{k} has {n}" for k, n in per_pair.items()))
        npairs = max(per_pair.values(), default=1)
        for k, a in values.items():
            object.__setattr__(self, k, np.array(np.broadcast_to(a, (npairs,))))
        if self.law not in LAWS:
            raise ValueError(f"law must be one of {LAWS}, got {self.law!r}")
        if np.any(self.kn <= 0) or np.any(self.kt <= 0):
            raise ValueError("contact stiffnesses kn, kt must be positive")
        if np.any(self.mu < 0) or np.any(self.N0 < 0) or np.any(self.gap < 0):
            raise ValueError("mu, N0 and gap must be non-negative")
        if np.any((self.N0 > 0) & (self.gap > 0)):
            raise ValueError("a pair has either a preload N0 or a gap, not both")

    @property
    def npairs(self) -> int:
        return self.kn.size

    def for_pairs(self, npairs: int) -> "FrictionContacts":
        """These parameters on ``npairs`` pairs: parameters given once (scalars) hold for every pair;
        parameters given per pair must be ``npairs`` of them (``ValueError`` naming the parameter)."""
        if self.npairs == npairs:
            return self
        if self.npairs != 1:
            raise ValueError(f"FrictionContacts: parameters given for {self.npairs} contact pairs, the "
                             f"structure's B has {npairs} pairs ({3 * npairs} rows: n, t1, t2 per pair)")
        return dataclasses.replace(self, **{k: np.repeat(getattr(self, k), npairs) for k in PARAMETERS})

    def static_force(self) -> np.ndarray:
        """Contact force at d = 0 (the static equilibrium), shape ``(npairs, 3)``: ``(N0, 0, 0)``."""
        lam = np.zeros((self.npairs, 3))
        lam[:, 0] = np.maximum(self.N0 - self.kn * self.gap, 0.0)
        return lam

    def stuck_stiffness(self) -> np.ndarray:
        """Stiffness ``(npairs, 3)`` of the linearised stuck system: ``(kn, kt, kt)`` on preloaded
        pairs (``kt`` only if μ > 0), zero on pairs with a gap or without preload."""
        return spring_diagonal(*stuck_springs(self.kn, self.kt, self.mu, self.N0 > 0), self.npairs)


@dataclass
class ContactAFT:
    """AFT result for all pairs: force coefficients ``lam`` ``(npairs, 3, C)``, their Jacobian
    ``jac[q, i, c, j, c'] = ∂lam[q, i, c] / ∂d[q, j, c']`` (or None), the time signals, and the
    periodic slider state at the period start ``memory`` ``(npairs, 2)``."""

    lam: np.ndarray
    jac: np.ndarray | None
    normal: np.ndarray
    tangential: np.ndarray
    memory: np.ndarray


def contact_aft(contacts: FrictionContacts, fourier: Fourier, d: np.ndarray,
                jacobian: bool | str = True, memory: np.ndarray | None = None, tol: float = 1e-13,
                max_periods: int = 500) -> ContactAFT:
    """Periodic contact forces of relative displacements ``d`` ``(npairs, 3, C)`` (slots of
    :mod:`ringdamper.nonlinear.fourier`), with the analytical Jacobian if ``jacobian`` (``"dc"``: only
    its columns for the mean values, ``jac[..., :1]``, which the rigid-body gauge needs).
    ``memory`` ``(npairs, 2)``: slider positions before the period (default 0, the static state).

    ``tol``/``max_periods`` control the periodicity check of the Coulomb march.
    """
    cp = contacts
    E, F = fourier.E, fourier.F
    memory = np.zeros((d.shape[0], 2)) if memory is None else memory
    if jacobian == "dc" and cp.law == "coulomb":
        full = contact_aft(contacts, fourier, d, True, memory, tol, max_periods)
        full.jac = full.jac[..., :1]
        return full
    basis = E[:, :1] if jacobian == "dc" else E
    dt = fourier.synth(d)                                    # (np, 3, Nt)
    N = cp.N0[:, None] + cp.kn[:, None] * (dt[:, 0] - cp.gap[:, None])
    closed = N > 0
    N = np.where(closed, N, 0.0)
    r = cp.mu[:, None] * N / cp.kt[:, None]                  # slip radius (np, Nt)
    if cp.law == "jenkins":
        T, dT = _jenkins(cp, basis, dt[:, 1:], r, closed, bool(jacobian), memory)
    else:
        T, dT = _coulomb(cp, E, dt[:, 1:], r, closed, jacobian, memory, tol, max_periods)
    lam = np.concatenate([fourier.analyse(N)[:, None], fourier.analyse(T)], axis=1)
    jac = None
    if jacobian:
        npairs, C, Cb = d.shape[0], fourier.C, basis.shape[1]
        jac = np.zeros((npairs, 3, C, 3, Cb))
        jac[:, 0, :, 0, :] = (F * (cp.kn[:, None] * closed)[:, None, :]) @ basis
        jac[:, 1:] = np.matmul(F, dT).reshape(npairs, 2, C, 3, Cb)
    w_end = dt[:, 1:, -1] - T[:, :, -1] / cp.kt[:, None]          # slider at the period end
    return ContactAFT(lam=lam, jac=jac, normal=N, tangential=T, memory=w_end)


def play_operator(lo: np.ndarray, hi: np.ndarray, w0: np.ndarray | float = 0.0):
    """Periodic steady state of the play operator ``w_k = clip(w_{k−1}, lo_k, hi_k)``.

    ``lo ≤ hi`` have shape ``(..., Nt)``, ``w0`` is the memory before the first period. Returns
    ``w`` and ``src`` (same shape): ``src = −1`` if ``w_k`` is the memory, ``s`` if it is ``lo_s``,
    ``Nt + s`` if it is ``hi_s``. Clamps compose as ``clip(clip(x, a1, b1), a2, b2) =
    clip(x, clip(a1, a2, b2), clip(b1, a2, b2))``; a Hillis–Steele scan builds the prefix maps.
    """
    nt = lo.shape[-1]
    a, b = lo.copy(), hi.copy()
    sa = np.broadcast_to(np.arange(nt), lo.shape).copy()
    sb = sa + nt
    step = 1
    while step < nt:
        ea, eb, esa, esb = a[..., :-step], b[..., :-step], sa[..., :-step], sb[..., :-step]
        la, lb, lsa, lsb = a[..., step:], b[..., step:], sa[..., step:], sb[..., step:]
        na, nsa = _clip_with_source(ea, esa, la, lb, lsa, lsb)
        nb, nsb = _clip_with_source(eb, esb, la, lb, lsa, lsb)
        a[..., step:], b[..., step:], sa[..., step:], sb[..., step:] = na, nb, nsa, nsb
        step *= 2
    w0 = np.broadcast_to(np.asarray(w0, float), lo.shape[:-1])
    start, s_start = _clip_with_source(w0, np.full(w0.shape, -1), a[..., -1], b[..., -1],
                                       sa[..., -1], sb[..., -1])
    w, src = _clip_with_source(start[..., None], s_start[..., None], a, b, sa, sb)
    if not np.array_equal(w[..., -1], start):       # one more period must reproduce the start
        raise RuntimeError("play operator: the marched state is not periodic")
    return w, src


def _clip_with_source(x, sx, lo, hi, slo, shi):
    """``clip(x, lo, hi)`` and its source. A tie goes to the bound: a value equal to a bound
    moves with it (the memory, source −1, is constant and would drop that derivative when the
    march restarts from its own periodic state)."""
    below, above = x <= lo, x >= hi
    return (np.where(below, lo, np.where(above, hi, x)),
            np.where(below, slo, np.where(above, shi, sx)))


def _jenkins(cp, E, d, r, closed, jacobian, memory):
    """Two independent Jenkins elements: forces ``(np, 2, Nt)`` and ``∂T/∂c`` ``(np, 2, Nt, 3C)``
    for the coefficients of the basis ``E`` (Nt × C: all slots, or the mean only)."""
    kt = cp.kt[:, None, None]
    w, src = play_operator(d - r[:, None], d + r[:, None], memory)
    T = kt * (d - w)
    if not jacobian:
        return T, None
    nt, C = E.shape
    npairs = d.shape[0]
    sourced = src >= 0
    s = np.where(sourced, src % nt, 0)
    sign = np.where(src >= nt, -1.0, 1.0) * sourced          # lo source: +1, hi: −1, memory: 0
    Es = E[s] * sourced[..., None]                           # (np, 2, Nt, C)
    chi = np.take_along_axis(np.broadcast_to(closed[:, None], s.shape), s, axis=-1)
    dT = np.zeros((npairs, 2, nt, 3, C))
    dT[:, :, :, 0] = (cp.mu * cp.kn)[:, None, None, None] * (sign * chi)[..., None] * Es
    for j in range(2):
        dT[:, j, :, j + 1] = cp.kt[:, None, None] * (E[None] - Es[:, j])
    return T, dT.reshape(npairs, 2, nt, 3 * C)


def _coulomb(cp, E, d, r, closed, jacobian, memory, tol, max_periods):
    """Isotropic Coulomb slider, marched period after period until the state at the period start
    repeats; derivatives are carried along in forward mode (:class:`_Dual`)."""
    npairs, _, nt = d.shape
    C = E.shape[1]
    zero = np.zeros((npairs, 3 * C)) if jacobian else None

    def signal(k):                                       # d_t1, d_t2 and r at sample k, with tangents
        if not jacobian:
            return _Dual(d[:, 0, k]), _Dual(d[:, 1, k]), _Dual(r[:, k])
        t1, t2, tr = zero.copy(), zero.copy(), zero.copy()
        t1[:, C:2 * C] = E[k]
        t2[:, 2 * C:] = E[k]
        tr[:, :C] = ((cp.mu * cp.kn / cp.kt) * closed[:, k])[:, None] * E[k]
        return _Dual(d[:, 0, k], t1), _Dual(d[:, 1, k], t2), _Dual(r[:, k], tr)

    samples = [signal(k) for k in range(nt)]
    w = (_Dual(memory[:, 0].astype(float), zero), _Dual(memory[:, 1].astype(float), zero))
    prev = samples[-1]
    scale = np.max(np.abs(d)) + np.max(r) + np.finfo(float).tiny
    W = np.empty((npairs, 2, nt))
    dW = np.empty((npairs, 2, nt, 3 * C)) if jacobian else None
    for _ in range(max_periods):
        start = w
        for k in range(nt):
            w = _tractrix_step(w, prev, samples[k])
            prev = samples[k]
            W[:, 0, k], W[:, 1, k] = w[0].v, w[1].v
            if jacobian:
                dW[:, 0, k], dW[:, 1, k] = w[0].t, w[1].t
        change = max(np.max(np.abs(w[i].v - start[i].v)) for i in range(2)) / scale
        if jacobian:
            change = max(change, max(np.max(np.abs(w[i].t - start[i].t)) for i in range(2))
                         / (1.0 + np.max(np.abs(dW))))
        if change <= tol:
            break
    else:
        raise RuntimeError(f"Coulomb hysteresis not periodic after {max_periods} periods")
    kt = cp.kt[:, None, None]
    T = kt * (d - W)
    if not jacobian:
        return T, None
    dd = np.zeros((2, nt, 3 * C))
    dd[0, :, C:2 * C] = E
    dd[1, :, 2 * C:] = E
    return T, kt[..., None] * (dd[None] - dW)


def _tractrix_step(w, prev, cur):
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


def dissipated_energy(d: np.ndarray, lam: np.ndarray) -> np.ndarray:
    """Energy dissipated per cycle, ``∮ λ · dd = π Σ_h h (λa_h db_h − λb_h da_h)`` [J], summed
    over the last-but-one axis (directions) of slot arrays ``(..., 3, C)``."""
    H = (d.shape[-1] - 1) // 2
    h = np.arange(1, H + 1)
    per_dir = np.pi * np.sum(h * (lam[..., 1::2] * d[..., 2::2] - lam[..., 2::2] * d[..., 1::2]), -1)
    return per_dir.sum(-1)
