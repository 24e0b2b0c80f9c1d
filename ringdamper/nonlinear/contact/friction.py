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
from ringdamper.nonlinear.contact.coulomb import coulomb_slider
from ringdamper.nonlinear.contact.play import play_operator
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

    #: the contact forces do not depend on velocity (the interface of a nonlinearity, see :meth:`aft`)
    velocity_dependent = False

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

    def aft(self, fourier: Fourier, d: np.ndarray, jacobian: bool | str = True,
            memory: np.ndarray | None = None, omega: float | None = None) -> "ContactAFT":
        """:func:`contact_aft` of these contacts (the interface the harmonic balance asks of a
        nonlinearity, shared with :class:`ringdamper.nonlinear.contact.elements.Elements`); the contact forces
        do not depend on velocity, so ``omega`` is not used."""
        return contact_aft(self, fourier, d, jacobian, memory)

    def stiffness_scale(self) -> float:
        """The largest contact stiffness [N/m] (the scale of the rigid-body hold test)."""
        return max(np.max(self.kn), np.max(self.kt))

    def linear_limit(self, c: np.ndarray) -> float:
        """Smallest amplitude factor at which the motion ``α |c|`` (``c`` ``(npairs, 3)``, harmonic 1
        of a linear stuck mode) would make a preloaded pair slip (``kt |d_t| = μ N0``) or open
        (``kn |d_n| = N0``), or a gapped pair close."""
        d = np.abs(c)
        with np.errstate(divide="ignore"):
            slip = self.mu * self.N0 / (self.kt * np.max(d[:, 1:], axis=1))
            open_ = np.where(self.N0 > 0, self.N0 / self.kn, self.gap) / d[:, 0]
        lim = np.min(np.r_[slip[self.N0 > 0], open_, np.inf])
        return lim if np.isfinite(lim) and lim > 0 else np.inf

    def stick_limit(self, c: np.ndarray) -> float:
        """Largest amplitude factor up to which ``d(θ) = α Re(c e^{iθ})`` (``c`` ``(npairs, 3)``)
        keeps every pair on the linearised stuck law at every instant: no preloaded pair slips or opens,
        no gapped pair closes (``inf`` if none ever does). A Jenkins direction j sticks while
        ``kt |d_j(θ)| ≤ μ (N0 + kn d_n(θ))`` for all θ, i.e. ``α max_± |kt c_j ± μ kn c_n| ≤ μ N0`` (the
        normal force varies with the motion); the normal force stays positive while ``α kn |c_n| <
        N0``; a gap stays open while ``α |c_n| < gap``. A pair without friction (μ = 0) carries no
        tangential force in either state."""
        kn, kt, mu, n0 = self.kn, self.kt, self.mu, self.N0
        load = np.maximum(np.abs(kt[:, None] * c[:, 1:] - (mu * kn * c[:, 0])[:, None]),
                          np.abs(kt[:, None] * c[:, 1:] + (mu * kn * c[:, 0])[:, None])).max(axis=1)
        with np.errstate(divide="ignore", invalid="ignore"):
            slip = np.where((n0 > 0) & (mu > 0), mu * n0 / load, np.inf)
            normal = np.where(n0 > 0, n0 / (kn * np.abs(c[:, 0])), self.gap / np.abs(c[:, 0]))
        lim = float(np.min(np.r_[slip, normal, np.inf]))
        return lim if lim > 0 else 0.0

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
    ``jac[q, i, c, j, c'] = ∂lam[q, i, c] / ∂d[q, j, c']`` (or None), the time signals, the
    periodic slider state at the period start ``memory`` ``(npairs, 2)`` and, for forces that depend
    on velocity, ``dlam_domega`` ``∂lam/∂ω`` and (with the full Jacobian) the velocity Jacobian
    ``jac_velocity[q, i, c, j, c'] = ∂lam[q, i, c] / ∂v[q, j, c']``, ``v`` the coefficients of the
    relative velocity taken apart from ``d`` (None: they do not depend on velocity)."""

    lam: np.ndarray
    jac: np.ndarray | None
    normal: np.ndarray
    tangential: np.ndarray
    memory: np.ndarray
    dlam_domega: np.ndarray | None = None
    jac_velocity: np.ndarray | None = None


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
    """Isotropic Coulomb slider (:func:`ringdamper.nonlinear.contact.coulomb.coulomb_slider`): forces
    ``(np, 2, Nt)`` and ``∂T/∂c`` ``(np, 2, Nt, 3C)``."""
    W, dW = coulomb_slider(cp.mu * cp.kn / cp.kt, E, d, r, closed, bool(jacobian), memory, tol, max_periods)
    kt = cp.kt[:, None, None]
    T = kt * (d - W)
    if not jacobian:
        return T, None
    nt, C = E.shape
    dd = np.zeros((2, nt, 3 * C))
    dd[0, :, C:2 * C] = E
    dd[1, :, 2 * C:] = E
    return T, kt[..., None] * (dd[None] - dW)


def dissipated_energy(d: np.ndarray, lam: np.ndarray) -> np.ndarray:
    """Energy dissipated per cycle, ``∮ λ · dd = π Σ_h h (λa_h db_h − λb_h da_h)`` [J], summed
    over the last-but-one axis (directions) of slot arrays ``(..., 3, C)``."""
    H = (d.shape[-1] - 1) // 2
    h = np.arange(1, H + 1)
    per_dir = np.pi * np.sum(h * (lam[..., 1::2] * d[..., 2::2] - lam[..., 2::2] * d[..., 1::2]), -1)
    return per_dir.sum(-1)
