"""Nonlinear elements on a user's structure, each acting through its own local coordinates.

An element acts through ``k`` local coordinates ``u = wᵀ q`` (``w``: a vector of the structure's
DoFs, or an ``(n, k)`` matrix) with the force ``wᵀ``-transposed back onto the DoFs, ``f_q = w f(u)``.
In the harmonic balance its forces are evaluated by AFT: the harmonics of ``u`` sampled at ``Nt``
instants, the force computed there, analysed back, and the analytic Jacobian
``∂f_c/∂u_c' = F diag(∂f/∂u) E`` (memoryless elements) or through the play operator's sources
(hysteretic ones). Forces are measured from the static state ``u = 0`` (the structure's equilibrium):
an element must exert no force there.

* :class:`CubicSpring` ``f = k3 u³`` (Duffing);
* :class:`UnilateralSpring` ``f = k max(u − gap, 0)``, ``gap ≥ 0`` (a stop closing at ``u = gap``);
* :class:`Jenkins` ``f = kt (u − s)``, slider ``s`` held while ``|f| < F_s`` (elastic dry friction, one
  direction; the memory before the period is the static state ``s = 0``, as for the 3-D contact);
* :class:`TanhFriction` ``f = F_s tanh(u̇/ε)`` (dry friction regularised in velocity). Its force depends
  on the velocity ``u̇ = ω ∂u/∂τ``, hence on ω: the AFT also returns ``∂f_c/∂ω``, which the harmonic
  balance adds to its ω column, and :meth:`Element.velocity_jacobian` gives ``∂f_c/∂v_c'``, the
  velocity's own Jacobian, which Hill's stability adds to its damping
  (:mod:`ringdamper.nonlinear.harmonic_balance.stability`).

:class:`Elements` gathers any number of them, of any kind, into the set the harmonic balance takes in
place of the 3-D contact pairs (:class:`ringdamper.nonlinear.contact.friction.FrictionContacts`): its ``B``
(:attr:`Elements.B`) gives each element three rows of local coordinates (the ``k`` of its ``w``, the
others zero, which carry no force), and it answers the questions the analyses ask of the contacts
(forces and Jacobian, static force, stuck stiffness, amplitude up to which the system stays linear).
"""
from __future__ import annotations

from abc import ABC, abstractmethod

import numpy as np

from ringdamper.nonlinear.contact.friction import ContactAFT, dissipated_energy
from ringdamper.nonlinear.contact.play import play_operator
from ringdamper.nonlinear.fourier import Fourier

#: local coordinates an element may have (the rows each element gets in :attr:`Elements.B`)
MAX_COORDINATES = 3


class Element(ABC):
    """One nonlinear element acting through the local coordinates ``u = wᵀ q``.

    ``local_coordinates``: how many the element has (None: any up to :data:`MAX_COORDINATES`);
    ``positive``: parameters that must be > 0 (every parameter must be a finite scalar ≥ 0)."""

    local_coordinates: int | None = 1
    positive: tuple = ()

    def __init__(self, w, **parameters):
        name = type(self).__name__
        w = np.asarray(w, float)
        self.w = w[:, None] if w.ndim == 1 else w
        if self.w.ndim != 2 or not 1 <= self.w.shape[1] <= MAX_COORDINATES:
            raise ValueError(f"{name}.w: expected shape (n,) or (n, k) with k <= {MAX_COORDINATES}, "
                             f"got {np.shape(w)}")
        if self.local_coordinates is not None and self.n_local != self.local_coordinates:
            raise ValueError(f"{name}.w: expected {self.local_coordinates} local coordinate(s), got {self.n_local}")
        for key, value in parameters.items():
            if np.shape(value) != ():
                raise ValueError(f"{name}.{key}: expected a scalar, got shape {np.shape(value)}")
            if not np.isfinite(value) or value < 0 or (key in self.positive and value == 0):
                bound = "> 0" if key in self.positive else ">= 0"
                raise ValueError(f"{name}.{key}: expected a finite value {bound}, got {value}")
            setattr(self, key, float(value))

    @property
    def n_local(self) -> int:
        """Number of local coordinates."""
        return self.w.shape[1]

    #: the force depends on the velocity
    velocity_dependent = False

    @abstractmethod
    def aft(self, fourier: Fourier, u: np.ndarray, jacobian: bool, omega: float | None = None):
        """Force coefficients ``(k, C)`` of the local coordinates' coefficients ``u`` ``(k, C)`` at the
        frequency ``omega``, (``jacobian``) their Jacobian ``(k, C, k, C)`` and ``∂f/∂ω`` ``(k, C)``
        (None for forces that do not depend on velocity)."""

    def stuck_stiffness(self) -> np.ndarray:
        """Stiffness ``(k,)`` of the element linearised at the static state (0: no force there)."""
        return np.zeros(self.n_local)

    def stick_limit(self, c: np.ndarray) -> float:
        """Largest amplitude factor ``α`` up to which ``u(θ) = α Re(c e^{iθ})`` (``c`` ``(k,)``
        complex) keeps the element on its linearisation (:meth:`stuck_stiffness`) at every instant;
        0 when it is nonlinear at any amplitude, ``inf`` when never."""
        return 0.0

    def linear_limit(self, c: np.ndarray) -> float:
        """Amplitude factor at which a discrete event (a stop closing, a slider slipping) first
        happens along ``α Re(c e^{iθ})``; ``inf`` when the element has none."""
        return self.stick_limit(c) if self.stick_limit(c) > 0 else np.inf

    def stiffness_scale(self) -> float:
        """A stiffness of the element [N/m] (the scale of the rigid-body hold test, 0 if none)."""
        return float(np.max(self.stuck_stiffness(), initial=0.0))

    def rest_damping(self) -> np.ndarray:
        """Viscous damping ``(k,)`` [N s/m] of the element linearised at rest (0: none)."""
        return np.zeros(self.n_local)

    def velocity_jacobian(self, fourier: Fourier, u: np.ndarray, omega: float) -> np.ndarray | None:
        """``∂f_c/∂v_c'`` ``(k, C, k, C)`` at the coefficients ``u`` ``(k, C)`` and the frequency ``omega``,
        ``v`` the coefficients of the velocity ``u̇`` taken apart from ``u`` (the Jacobian of :meth:`aft`
        holds ``u̇ = ω ∂u/∂τ`` tied to ``u``); None for forces that do not depend on velocity."""
        return None


class _Memoryless(Element):
    """An element whose force depends on the present local displacement and velocity only: AFT with
    ``∂f_c/∂u_c' = F diag(∂f/∂u) E + ω F diag(∂f/∂u̇) dE`` and ``∂f_c/∂ω = F (∂f/∂u̇ · dE u)``; velocity
    Jacobian ``∂f_c/∂v_c' = F diag(∂f/∂u̇) E``."""

    @abstractmethod
    def force(self, u: np.ndarray, v: np.ndarray):
        """Force ``(k, Nt)`` at the displacement and velocity samples ``u``, ``v`` ``(k, Nt)`` (``v`` None
        for an element that does not depend on velocity), and its derivatives ``(k, k, Nt)`` with
        respect to ``u`` and to ``v`` (None: no velocity dependence)."""

    def _sampled(self, fourier, u, omega):
        """:meth:`force` and its derivatives at the samples of ``u`` and of ``u̇ = ω ∂u/∂τ``, and
        ``∂u/∂τ`` there (None for an element that does not depend on velocity)."""
        if self.velocity_dependent and omega is None:
            raise ValueError(f"{type(self).__name__}: the force depends on velocity, the AFT needs omega")
        rate = u @ fourier.dE.T if self.velocity_dependent else None      # ∂u/∂τ at the samples
        return self.force(fourier.synth(u), None if rate is None else omega * rate), rate

    def aft(self, fourier, u, jacobian, omega=None):
        (f, df_du, df_dv), rate = self._sampled(fourier, u, omega)
        lam = fourier.analyse(f)
        if not jacobian:
            return lam, None, None
        jac = _projected(fourier, df_du, fourier.E)
        if df_dv is None:
            return lam, jac, None
        jac += omega * _projected(fourier, df_dv, fourier.dE)
        return lam, jac, fourier.analyse(np.einsum("ijt,jt->it", df_dv, rate))

    def velocity_jacobian(self, fourier, u, omega):
        if not self.velocity_dependent:
            return None
        (_, _, df_dv), _ = self._sampled(fourier, u, omega)
        return _projected(fourier, df_dv, fourier.E)


def _projected(fourier: Fourier, df: np.ndarray, basis: np.ndarray) -> np.ndarray:
    """``F diag(df) basis`` ``(k, C, k, C)`` of the sampled derivatives ``df`` ``(k, k, Nt)``: the
    coefficients of ``df · x`` for the samples ``x = basis c`` (``basis`` ``E`` or ``dE``)."""
    return np.einsum("ct,ijt,td->icjd", fourier.F, df, basis)


class CubicSpring(_Memoryless):
    """``f = k3 u³`` [N] on one local coordinate (``k3`` in N/m³)."""

    def __init__(self, w, k3: float):
        super().__init__(w, k3=k3)

    def force(self, u, v):
        return self.k3 * u ** 3, (3.0 * self.k3 * u ** 2)[:, None], None


class UnilateralSpring(_Memoryless):
    """``f = k max(u − gap, 0)`` [N] on one local coordinate: a stop of stiffness ``k`` (``stiffness``,
    N/m) that closes when ``u`` reaches ``gap`` (≥ 0, m)."""

    def __init__(self, w, stiffness: float, gap: float = 0.0):
        super().__init__(w, stiffness=stiffness, gap=gap)

    def force(self, u, v):
        closed = u > self.gap
        return self.stiffness * np.where(closed, u - self.gap, 0.0), (self.stiffness * closed)[:, None], None

    def stick_limit(self, c):
        """The stop stays open while ``α |c| < gap`` (closed at any amplitude when ``gap = 0``)."""
        size = float(np.abs(c[0]))
        return self.gap / size if size > 0 else np.inf

    def stiffness_scale(self) -> float:
        return self.stiffness


class Jenkins(Element):
    """Elastic dry friction on one local coordinate: a spring ``kt`` [N/m] in series with a slider
    that slips at the force ``slip_force`` [N]. The slider follows the play operator
    ``s_k = clip(s_{k−1}, u_k − r, u_k + r)``, ``r = slip_force / kt``, from the static state
    ``s = 0``; ``∂s_k/∂u`` is that of the sample the slider value comes from
    (:func:`ringdamper.nonlinear.contact.play.play_operator`)."""

    positive = ("kt",)

    def __init__(self, w, kt: float, slip_force: float):
        super().__init__(w, kt=kt, slip_force=slip_force)

    def aft(self, fourier, u, jacobian, omega=None):
        E = fourier.E
        x = fourier.synth(u)[0]
        r = self.slip_force / self.kt
        s, src = play_operator(x - r, x + r)
        lam = fourier.analyse(self.kt * (x - s))[None]
        if not jacobian:
            return lam, None, None
        sourced = src >= 0
        ds = E[np.where(sourced, src % fourier.nt, 0)] * sourced[:, None]          # (Nt, C)
        return lam, (fourier.F @ (self.kt * (E - ds)))[None, :, None, :], None

    def stuck_stiffness(self):
        return np.array([self.kt])

    def stick_limit(self, c):
        """Sticks while ``kt α |c| ≤ slip_force``."""
        size = float(np.abs(c[0]))
        return self.slip_force / (self.kt * size) if size > 0 else np.inf


class TanhFriction(_Memoryless):
    """Dry friction regularised in velocity on one local coordinate: ``f = slip_force · tanh(u̇/eps)``
    [N] (``eps`` [m/s]: the velocity over which the force builds up; a viscous damper
    ``slip_force/eps`` for ``|u̇| ≪ eps``, Coulomb's ``± slip_force`` for ``|u̇| ≫ eps``)."""

    velocity_dependent = True
    positive = ("eps",)

    def __init__(self, w, slip_force: float, eps: float):
        super().__init__(w, slip_force=slip_force, eps=eps)

    def rest_damping(self):
        """A damper ``slip_force / eps`` while ``|u̇| ≪ eps``."""
        return np.array([self.slip_force / self.eps])

    def force(self, u, v):
        t = np.tanh(v / self.eps)
        return self.slip_force * t, np.zeros((1, 1, u.shape[-1])), (self.slip_force / self.eps * (1 - t * t))[:, None]


class Elements:
    """A set of elements of any kind on a structure with ``n_dofs`` DoFs, in the form the harmonic
    balance takes (module docstring): ``elements.B`` is the ``B`` of the :class:`Structure`, and the
    set is passed where the analyses take the contacts (``epmc(structure, elements, …)``)."""

    def __init__(self, elements, n_dofs: int):
        self.elements = list(elements)
        if not self.elements:
            raise ValueError("Elements: expected at least one element")
        for i, e in enumerate(self.elements):
            if not isinstance(e, Element):
                raise ValueError(f"Elements[{i}]: expected an Element, got {type(e).__name__}")
            if e.w.shape[0] != n_dofs:
                raise ValueError(f"Elements[{i}] ({type(e).__name__}).w: expected {n_dofs} rows (the "
                                 f"structure's DoFs), got {e.w.shape[0]}")
        self.n_dofs = n_dofs

    @property
    def npairs(self) -> int:
        """Number of elements (each owns three rows of ``B``, as a contact pair does)."""
        return len(self.elements)

    @property
    def B(self) -> np.ndarray:
        """``(3 · npairs, n_dofs)``: element ``e``'s local coordinates ``wᵀ`` in rows ``3e .. 3e + k − 1``."""
        B = np.zeros((MAX_COORDINATES * self.npairs, self.n_dofs))
        for i, e in enumerate(self.elements):
            B[MAX_COORDINATES * i:MAX_COORDINATES * i + e.n_local] = e.w.T
        return B

    def for_pairs(self, npairs: int) -> "Elements":
        if npairs != self.npairs:
            raise ValueError(f"Elements: {self.npairs} elements, the structure's B has {npairs} blocks of 3 "
                             "rows (build the structure with elements.B)")
        return self

    @property
    def velocity_dependent(self) -> bool:
        """Some element's force depends on velocity (hence on ω)."""
        return any(e.velocity_dependent for e in self.elements)

    def aft(self, fourier: Fourier, d: np.ndarray, jacobian: bool | str = True, memory=None,
            omega: float | None = None) -> ContactAFT:
        """Forces ``lam`` ``(npairs, 3, C)`` of the local coordinates' coefficients ``d``
        ``(npairs, 3, C)`` at the frequency ``omega``, (``jacobian``) their Jacobian
        ``(npairs, 3, C, 3, C)`` (``"dc"``: its columns of the mean values only) and, if some element
        depends on velocity, ``dlam_domega`` and (full Jacobian) ``jac_velocity``
        (:meth:`Element.velocity_jacobian`). ``memory`` is not used: every hysteretic element starts
        from the static state."""
        npairs, _, C = d.shape
        lam = np.zeros((npairs, 3, C))
        jac = np.zeros((npairs, 3, C, 3, C)) if jacobian else None
        dlam_domega = np.zeros((npairs, 3, C)) if jacobian and self.velocity_dependent else None
        jac_velocity = np.zeros_like(jac) if dlam_domega is not None and jacobian != "dc" else None
        for i, e in enumerate(self.elements):
            k = e.n_local
            f, df, df_dw = e.aft(fourier, d[i, :k], bool(jacobian), omega)
            lam[i, :k] = f
            if jacobian:
                jac[i, :k, :, :k] = df
            if df_dw is not None:
                dlam_domega[i, :k] = df_dw
            if jac_velocity is not None and e.velocity_dependent:
                jac_velocity[i, :k, :, :k] = e.velocity_jacobian(fourier, d[i, :k], omega)
        if jacobian == "dc":
            jac = jac[..., :1]
        return ContactAFT(lam=lam, jac=jac, normal=None, tangential=None, memory=None, dlam_domega=dlam_domega,
                          jac_velocity=jac_velocity)

    def energy(self, d: np.ndarray, lam: np.ndarray) -> np.ndarray:
        """Energy each element dissipates per cycle [J], ``∮ f · du`` of its local coordinates ``d`` and
        forces ``lam`` ``(npairs, 3, C)`` (:func:`ringdamper.nonlinear.contact.friction.dissipated_energy`;
        zero for the conservative elements, up to the AFT's discretisation)."""
        return dissipated_energy(d, lam)

    def static_force(self) -> np.ndarray:
        """No element exerts a force at the static state: zeros ``(npairs, 3)``."""
        return np.zeros((self.npairs, 3))

    def stuck_stiffness(self) -> np.ndarray:
        out = np.zeros((self.npairs, 3))
        for i, e in enumerate(self.elements):
            out[i, :e.n_local] = e.stuck_stiffness()
        return out

    def stiffness_scale(self) -> float:
        return max(e.stiffness_scale() for e in self.elements)

    def rest_damping(self) -> np.ndarray:
        """Damping ``(npairs, 3)`` of the elements linearised at rest."""
        out = np.zeros((self.npairs, 3))
        for i, e in enumerate(self.elements):
            out[i, :e.n_local] = e.rest_damping()
        return out

    def stick_limit(self, c: np.ndarray) -> float:
        """Smallest :meth:`Element.stick_limit` over the elements, ``c`` ``(npairs, 3)``."""
        return min(e.stick_limit(c[i, :e.n_local]) for i, e in enumerate(self.elements))

    def linear_limit(self, c: np.ndarray) -> float:
        return min(e.linear_limit(c[i, :e.n_local]) for i, e in enumerate(self.elements))
