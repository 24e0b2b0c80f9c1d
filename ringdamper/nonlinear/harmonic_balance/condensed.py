"""Harmonic balance residual condensed exactly onto the contact coordinates (docs/design.md §3.4).

Per harmonic h the linear DoFs are eliminated by modal summation over *all* modes of
``(K_h, M_h)`` (:mod:`ringdamper.nonlinear.harmonic_balance.structure`). With modal damping ``c_r`` and the EPMC term
``−ξ M q̇`` (Krack 2015) the modal receptance is diagonal:

    z_r = ω_r² − h²ω² + i h ω (c_r − ξ),       η_{h,r} = (f_{h,r} − ψ_rᴴ Λ_h) / z_r,

with ``ψ_r = B_h φ_r`` and modal force ``f = γ Φᴴ F_h``. Damping that couples the modes (a ``C_h`` not
diagonal in them, :mod:`ringdamper.nonlinear.harmonic_balance.structure`) makes the receptance a full matrix: every mode
of that harmonic is then explicit, and its rows carry the coupling,
``z_S η_S + i h ω C_off η_S``. Otherwise most modes are condensed
(``r ∈ C_h``); a few are kept as explicit unknowns (``r ∈ S_h``): the zero-frequency modes of
harmonic 0 (rigid ring, see *gauge* below) and, optionally, modes whose ω_r lies near ``hω``, so the
receptance never passes a pole. Unknowns ``y``: the real slots of the contact relative
displacements ``d`` (slot-major, ``(C, p)``), then ``η_{h,S}`` (harmonic 0 real; ``h ≥ 1`` as
``(a; b)`` with ``η = a − ib``). Residual, same layout:

    r_{d,h} = D_h − Σ_{r∈C} ψ_r η_{h,r} − Σ_{r∈S} ψ_r η_{h,r},      r_{η,h} = z_S η_S − (f_S − Ψ_Sᴴ Λ_h),

with ``Λ_h`` the contact forces from the AFT (:mod:`ringdamper.nonlinear.contact.friction`) minus the static
contact force ``(N0, 0, 0)``: displacements are measured from the static equilibrium, where
that force is balanced by the static loads. The slider memory before the period is the static
state (slider at zero) at every evaluation, so a solution depends on its own unknowns only, not on
the continuation path: a pair that slips during the period has a unique periodic state anyway,
and a pair that sticks throughout keeps the static slider position projected onto the band of
positions that stick, ``[max_k(d_k − r_k), min_k(d_k + r_k)]``, i.e. it is pushed only as far as
the motion forces it (:func:`ringdamper.nonlinear.contact.play.play_operator`), independently of where
the period starts. (Carrying the last accepted point's slider state instead puts every pair that the
growing amplitude pushes exactly on its stick/slip kink at every accepted point; Newton then
cycles between the two sides.)

Jacobian: ``∂r/∂y = I + A_h K_c`` with ``A_h = [Ψ_C diag(1/z_C) Ψ_Cᴴ ; Ψ_Sᴴ]`` per harmonic and
``K_c`` the AFT Jacobian (block-diagonal over pairs), plus the explicit-mode blocks. The ω column is
``∂z/∂ω`` through the receptances plus, for forces that depend on velocity (the AFT's
``dlam_domega``, e.g. :class:`ringdamper.nonlinear.contact.elements.TanhFriction`), ``A_h ∂Λ_h/∂ω``. It is an
operator (:class:`CoreJacobian`): its product with a vector is the residual's linearisation,
``δr_{d,h} = δD_h + Ψ_C diag(1/z_C) Ψ_Cᴴ δΛ_h − Ψ_S δη_S``, ``δr_{η,h} = z_S δη_S + Ψ_Sᴴ δΛ_h``,
``δΛ = K_c δd`` (``O(p·m)`` per harmonic), and the matrix (``O(p²·m)``: the receptances ``G_h``) is
formed only for a factorisation.

Gauge (zero modes of harmonic 0, e.g. the ring's rotation and axial translation): their rows are
the rigid-body equilibria ``Ψ_Zᴴ Λ_0 = f_Z``. The mean position ``η_Z`` is determined only while
some contact holds it (stuck memory or a normal spring along the rigid motion). When the
contact stiffness along a rigid motion vanishes (all pairs it moves have lost their memory), the
system is singular: the equilibrium along that direction no longer involves ``η_Z`` and the
position is arbitrary. Those directions (null space of ``K_c Ψ_Z`` on the DC slots, by SVD) get
the explicit gauge ``η_Z = η_ref`` instead (``η_ref``: the last determined position, held by the
solve's :class:`GaugeState`), and the dropped equilibrium is returned as ``drift``: if non-zero at a
solution, no periodic solution exists (the free body ratchets).

Soft hold: "vanishes" means below ``gauge_tol`` (default 1 %) of one pair's stiffness times
``‖Ψ_Z‖₂``. Once the whole interface slips, a ring whose contact normals are tilted (κ1) is still
held along its rotation by the normal springs (the wedge effect), at ~2 % of its stuck hold. Its
mean position is then set by a spring that soft: near the release of the last stuck pairs it
slides by millimetres (far outside the small-displacement contact kinematics about the static
state) and the branch meets a singular point (σ_min/σ_max ≈ 3e-11 of the augmented Jacobian)
that no continuation passed on 6 of the first 40 campaign rings. Treating such a direction as
free (gauged, then pinned) removes it.

Pinning: a direction that lost its hold at an accepted point, or whose hold Newton found and
lost again within a failed step (:meth:`GaugeState.pin_seen`), stays gauged for the rest of
the branch (:meth:`GaugeState.pin`). Near the loss of hold the last holding pair cannot carry
the imbalance and the gauge position keeps it stuck, so neither equation set alone has a
solution and Newton cycles between them; the pinned direction behaves as a stop holding the
body at its last equilibrium position, and the force the stop takes is the reported ``drift``.

State. A :class:`CondensedHBM` is the fixed problem (structure, contacts, truncation, the receptance
series formed about one expansion point): nothing in it changes once it is built, so one model
serves any number of solves, in any order (the adaptive truncation shares one per H between the
points of a ring). What a solve carries from one evaluation to the next is its :class:`GaugeState`
(gauge reference, pinned directions, lost holds seen since the last accepted point), an immutable
value: :meth:`CondensedHBM.evaluate` takes one and returns, in :attr:`CoreEval.state`, the state
after that evaluation; :meth:`CondensedHBM.accepted`, :meth:`GaugeState.pin` and
:meth:`GaugeState.pin_seen` return new states. A problem built on the model
(:class:`ringdamper.nonlinear.harmonic_balance.epmc.EPMCProblem`,
:class:`ringdamper.nonlinear.harmonic_balance.forced.ForcedProblem`)
is one solve: it holds the state and replaces it by each evaluation's.
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ringdamper.nonlinear.contact.elements import Elements
from ringdamper.nonlinear.contact.friction import ContactAFT, FrictionContacts
from ringdamper.nonlinear.fourier import Fourier, real_block, real_vector, to_complex
from ringdamper.nonlinear.harmonic_balance.nonlinear_rows import StuckBasis, reduced_solver
from ringdamper.nonlinear.harmonic_balance.receptance import DampedReceptance, Receptance
from ringdamper.nonlinear.harmonic_balance.structure import Structure


@dataclass(frozen=True)
class GaugeState:
    """The gauge state of one solve (module docstring, *Gauge*, *Pinning*, *State*): ``reference``, the
    gauge position ``η_ref`` of the zero modes (nz,); ``pinned``, the directions gauged for good and
    ``seen``, those whose hold some evaluation since the last accepted point found lost (orthonormal
    columns in the zero-mode space, (nz, k)). Immutable (its arrays read-only): every change returns a
    new state. Built by :meth:`CondensedHBM.initial_gauge` or :meth:`CondensedHBM.gauge_at`."""

    reference: np.ndarray
    pinned: np.ndarray
    seen: np.ndarray

    def __post_init__(self):
        for name in ("reference", "pinned", "seen"):
            value = np.array(getattr(self, name), float)
            value.flags.writeable = False
            object.__setattr__(self, name, value)

    def pin(self, basis: np.ndarray) -> tuple["GaugeState", bool]:
        """The state with the directions ``basis`` (columns in the zero-mode space) gauged for good,
        and whether that added a direction."""
        merged = _span(self.pinned, basis)
        if merged.shape[1] == self.pinned.shape[1]:
            return self, False
        return replace(self, pinned=merged), True

    def pin_seen(self) -> tuple["GaugeState", bool]:
        """The state with the directions whose hold was lost in some evaluation since the last accepted
        point pinned (after a failed step: Newton cycled between holding and not holding) and none seen,
        and whether that added a direction."""
        state, added = self.pin(self.seen)
        return replace(state, seen=np.zeros_like(state.pinned[:, :0])), added


@dataclass(frozen=True)
class CoreEval:
    """One evaluation: residual ``r``, Jacobian ``J`` (core × core, a :class:`CoreJacobian`
    operator) and its columns for ω and ξ,
    the trivial unknowns (d slots of pairs with zero contact Jacobian: their columns are unit
    vectors), contact displacement/force slots ``d``, ``lam`` (C × p), modal coordinates ``eta[h]``
    of every mode, the AFT result, the gauge drift (equilibria dropped for the gauge), the
    gauged directions ``gauge`` (orthonormal columns in the zero-mode space, one per drift) and
    ``state``, the solve's :class:`GaugeState` after this evaluation (the lost holds it found added to
    those seen)."""

    r: np.ndarray
    J: "CoreJacobian | None"
    dr_domega: np.ndarray | None
    dr_dxi: np.ndarray | None
    trivial: np.ndarray | None
    d: np.ndarray
    lam: np.ndarray
    eta: list
    aft: ContactAFT
    drift: np.ndarray
    gauge: np.ndarray
    state: GaugeState


def structural_damping(structure: Structure, H: int, zeta_s: float | np.ndarray = 0.0) -> list | None:
    """Modal damping of harmonics ``0..H``: the coefficients ``c_r`` (:meth:`ModalHarmonic.damping`),
    the structure's own (``C`` or modal ratios) else ``2 ζ_s ω_r``, or the full matrix ``Φᴴ C Φ`` of a
    harmonic whose ``C`` couples the modes; None when neither damps."""
    if not structure.damped and not np.any(np.asarray(zeta_s) != 0):
        return None
    out = []
    for h in range(H + 1):
        m = structure.modal(h)
        c = m.damping(zeta_s)
        out.append(c if m.coupling is None else np.diag(c) + m.coupling)
    return out


class CondensedHBM:
    """Condensed HBM of one structure, contact set and harmonic truncation.

    ``explicit[h]``: indices of the modes of harmonic h kept as unknowns (the zero modes of
    harmonic 0 are always added). ``damping[h]``: modal damping coefficients ``c_r``, or the full
    modal damping matrix (m × m) where it couples the modes, which makes every mode of that
    harmonic explicit (None: no structural damping, as in the campaign's dNNM;
    :func:`structural_damping` gives the structure's). ``forced``: include the forcing vectors scaled by
    ``gamma``. ``gauge_tol``: a rigid-body direction whose DC contact stiffness (singular value
    of ``K_c Ψ_Z``) is below ``gauge_tol × max(kn, kt) × ‖Ψ_Z‖₂`` counts as not held (module
    docstring, *soft hold*). ``expansion``: the ``(ω, ξ)`` about which the receptance series of the
    condensed modes are formed (:meth:`receptance`; a solve's start point: the series then serves it
    and every point within its reach, to rounding); None: direct sums.

    ``nonlinear_rows``: factorisations may solve on the nonlinear contact rows only, through the stuck
    structure (:mod:`ringdamper.nonlinear.harmonic_balance.nonlinear_rows`, undamped models), where that
    system is the smaller (:meth:`CoreJacobian.reduced_solver`).

    Fixed once built (module docstring, *State*): setting an attribute raises.
    """

    def __init__(self, structure: Structure, contacts: FrictionContacts | Elements, H: int, nt: int,
                 explicit=None, damping=None, forced: bool = False, gamma: float = 0.0,
                 gauge_tol: float = 1e-2, expansion: tuple[float, float] | None = None,
                 nonlinear_rows: bool = False):
        if H > structure.H_max:
            raise ValueError(f"structure has harmonics up to {structure.H_max}, H={H} requested")
        contacts = contacts.for_pairs(structure.npairs)
        self.structure, self.contacts = structure, contacts
        self.H, self.fourier = H, Fourier(H, nt)
        self.C, self.p, self.npairs = 2 * H + 1, structure.p, structure.npairs
        self.n_d = self.C * self.p
        self.modal = [structure.modal(h) for h in range(H + 1)]
        self.damping, self.coupling = _split_damping(damping, self.modal)
        self.damped = damping is not None
        self.forced, self.gamma = forced, gamma
        self.static = contacts.static_force().ravel()
        self.S, self.Cset, self.eta_slices = [], [], []
        off = self.n_d
        for h, m in enumerate(self.modal):
            S = np.asarray([] if explicit is None else explicit[h], int)
            if h == 0:
                S = np.union1d(S, np.flatnonzero(m.zero))
            if self.coupling[h] is not None:
                S = np.arange(m.w2.size)
            mask = np.ones(m.w2.size, bool)
            mask[S] = False
            self.S.append(S)
            self.Cset.append(np.flatnonzero(mask))
            size = S.size * (1 if h == 0 else 2)
            self.eta_slices.append(slice(off, off + size))
            off += size
        self.n_core = off
        self.PsiH = [m.Psi.conj().T.copy() for m in self.modal]                 # Ψ_hᴴ
        self.PsiC = [m.Psi[:, Cs] for m, Cs in zip(self.modal, self.Cset)]     # condensed
        self.PsiS = [m.Psi[:, S] for m, S in zip(self.modal, self.S)]          # explicit
        self.PsiCH = [P.conj().T.copy() for P in self.PsiC]                    # Ψ_Cᴴ
        self.PsiSH = [P.conj().T.copy() for P in self.PsiS]                    # Ψ_Sᴴ
        self.receptances = [_receptance(h, m.w2[Cs], c[Cs], P, PH, coupled is not None, expansion)
                            for h, (m, Cs, P, PH, c, coupled)
                            in enumerate(zip(self.modal, self.Cset, self.PsiC, self.PsiCH, self.damping,
                                             self.coupling))]
        self.zero_modes = np.flatnonzero(self.modal[0].zero[self.S[0]])    # positions within S_0
        if self.zero_modes.size:
            PsiZ = self.modal[0].Psi[:, self.S[0][self.zero_modes]]
            if np.any(np.linalg.norm(PsiZ, axis=0) == 0):
                raise ValueError("a zero-frequency mode of harmonic 0 moves no contact: mechanism")
        kscale = contacts.stiffness_scale()
        self._null_tol = gauge_tol * kscale * (np.linalg.norm(PsiZ, 2) if self.zero_modes.size
                                               else 0.0)
        self.stuck = StuckBasis(self, contacts.stuck_stiffness(), None if expansion is None else expansion[0]) \
            if nonlinear_rows else None
        self._fixed = True

    def __setattr__(self, name, value):
        if "_fixed" in self.__dict__:
            raise AttributeError(f"CondensedHBM is fixed once built: cannot set {name!r} (a solve's "
                                 "gauge state is a GaugeState, passed to evaluate)")
        super().__setattr__(name, value)

    # ---- layout helpers -------------------------------------------------------------------
    def eta_explicit(self, y: np.ndarray, h: int) -> np.ndarray:
        v = y[self.eta_slices[h]]
        if h == 0:
            return v.astype(complex)
        s = v.size // 2
        return v[:s] - 1j * v[s:]

    def pack(self, d: np.ndarray, eta: list) -> np.ndarray:
        """Unknown vector from contact slots ``d`` (C × p) and the modal coordinates ``eta[h]``
        of all modes (only the explicit ones are stored)."""
        parts = [d.ravel()]
        for h in range(self.H + 1):
            e = eta[h][self.S[h]]
            parts.append(e.real if h == 0 else real_vector(e))
        return np.concatenate(parts)

    def slot_index(self, h: int, imag: bool, i: int) -> int:
        """Index in ``y`` of the cosine (``imag=False``) or sine slot of harmonic ``h ≥ 1`` of
        contact coordinate ``i``."""
        return (2 * h - 1 + int(imag)) * self.p + i

    def eta_index(self, h: int, k: int, imag: bool) -> int:
        """Index in ``y`` of the real (``a``) or sine (``b``) part of explicit mode ``k`` (position
        in ``S[h]``) of harmonic ``h``."""
        s = self.S[h].size
        return self.eta_slices[h].start + k + (s if imag else 0)

    # ---- gauge states (module docstring, *State*) -------------------------------------------
    def initial_gauge(self, reference: np.ndarray | None = None) -> GaugeState:
        """The gauge state a solve starts from: reference ``reference`` (the zero-mode positions while
        they are undetermined; default 0), nothing pinned or seen."""
        nz = self.zero_modes.size
        ref = np.zeros(nz) if reference is None else reference
        return GaugeState(reference=ref, pinned=np.zeros((nz, 0)), seen=np.zeros((nz, 0)))

    def gauge_at(self, y: np.ndarray, pinned: np.ndarray) -> GaugeState:
        """The gauge state of a solve from a point ``y`` (its unknowns; ω and ξ may follow) that was
        solved with the rigid-body directions ``pinned``: those pinned, no lost hold seen, and the gauge
        reference the zero-mode positions of ``y``."""
        reference = y[self.eta_slices[0].start + self.zero_modes] if self.zero_modes.size \
            else np.zeros(0)
        return GaugeState(reference=reference, pinned=pinned, seen=np.zeros_like(pinned[:, :0]))

    def accepted(self, gauge: GaugeState, y: np.ndarray, ev: "CoreEval") -> GaugeState:
        """The gauge state after the accepted continuation point ``y`` (evaluated as ``ev``): the
        reference takes the zero-mode positions of ``y`` (an undetermined rigid-body position keeps its
        last value), the directions gauged at ``ev`` are pinned and none is seen (module docstring)."""
        if not self.zero_modes.size:
            return gauge
        moved = replace(gauge, reference=y[self.eta_slices[0].start + self.zero_modes])
        pinned, _ = moved.pin(ev.gauge)
        return replace(pinned, seen=np.zeros_like(pinned.pinned[:, :0]))

    def relative_drift(self, ev: "CoreEval") -> float:
        """Largest dropped rigid-body equilibrium of ``ev`` relative to ``max|Ψ_0|·max|λ|``
        (0 when no rigid-body direction is gauged)."""
        if not ev.drift.size:
            return 0.0
        scale = np.max(np.abs(self.modal[0].Psi)) * max(np.max(np.abs(ev.lam)), 1e-300)
        return float(np.max(np.abs(ev.drift)) / scale)

    def core_scale(self, y: np.ndarray) -> np.ndarray:
        """Scale of every core unknown for convergence tests: contact slots by the largest of
        them, explicit modal coordinates by the largest of them or the modal equivalent of the
        contact scale, whichever is larger."""
        sc = np.empty(self.n_core)
        ds = max(np.max(np.abs(y[:self.n_d])), 1e-300)
        sc[:self.n_d] = ds
        if self.n_core > self.n_d:
            psi = max(np.max(np.abs(self.modal[h].Psi[:, self.S[h]]), initial=0.0)
                      for h in range(self.H + 1))
            sc[self.n_d:] = max(np.max(np.abs(y[self.n_d:])), ds / max(psi, 1e-300))
        return sc

    # ---- evaluation -----------------------------------------------------------------------
    def evaluate(self, y: np.ndarray, omega: float, xi: float, gauge: GaugeState,
                 jacobian: bool = True) -> CoreEval:
        """Residual at ``(y, ω, ξ)`` in the gauge state ``gauge`` and, if ``jacobian``, its
        linearisation: ``J`` as an operator (:class:`CoreJacobian`) and the ω and ξ columns. The state
        after the evaluation is :attr:`CoreEval.state` (``gauge`` itself is a value: unchanged)."""
        H, C, p, npairs = self.H, self.C, self.p, self.npairs
        d = y[:self.n_d].reshape(C, p)
        aft = self.contacts.aft(self.fourier, d.reshape(C, npairs, 3).transpose(1, 2, 0),
                                jacobian=True if jacobian else ("dc" if self.zero_modes.size else False),
                                omega=omega)
        lam = aft.lam.transpose(2, 0, 1).reshape(C, p).copy()
        lam[0] -= self.static
        D, Lam = to_complex(d, H), to_complex(lam, H)
        r = np.empty(self.n_core)
        dr_dw = np.zeros(self.n_core) if jacobian else None
        dr_dx = np.zeros(self.n_core) if jacobian else None
        dLam_dw = self._velocity_term(aft) if jacobian else None
        etas, impedances = [], []
        for h in range(H + 1):
            m, S, Cs = self.modal[h], self.S[h], self.Cset[h]
            z, dz_dw, dz_dx = self._modal_impedance(h, omega, xi)
            impedances.append(z)
            load = (self.gamma * m.f if self.forced else 0.0) - self.PsiH[h] @ Lam[h]
            eta_S = self.eta_explicit(y, h)
            zC = z[Cs]
            eta = np.empty(m.w2.size, complex)
            eta[Cs] = etaC = load[Cs] / zC
            eta[S] = eta_S
            etas.append(eta)
            self._put(r, h, D[h] - m.Psi @ eta, z[S] * eta_S + self._coupled(h, omega, eta_S) - load[S])
            if jacobian:                           # ω and ξ derivatives: only z (and the coupling) depend on them
                per_impedance = etaC / zC
                for vec, dz in ((dr_dw, dz_dw), (dr_dx, dz_dx)):
                    self._put(vec, h, self.PsiC[h] @ (per_impedance * dz[Cs]), dz[S] * eta_S)
                if h > 0 and self.coupling[h] is not None:
                    dr_dw[self.eta_slices[h]] += real_vector(self._coupled(h, 1.0, eta_S))
                if dLam_dw is not None:            # forces that depend on velocity: Λ depends on ω
                    extra = np.zeros(self.n_core)
                    self._put(extra, h, self.PsiC[h] @ ((self.PsiCH[h] @ dLam_dw[h]) / zC),
                              self.PsiSH[h] @ dLam_dw[h])
                    dr_dw += extra
        J = trivial = None
        if jacobian:
            active = np.any(aft.jac.reshape(npairs, -1) != 0, axis=1)
            trivial = np.zeros(self.n_core, bool)
            trivial[:self.n_d] = np.tile(np.repeat(~active, 3), C)
        drift, gauged, rotation, state = self._gauge(r, (dr_dw, dr_dx) if jacobian else (), y, aft.jac,
                                                     gauge)
        if jacobian:
            J = CoreJacobian(self, aft.jac, omega, xi, rotation, impedances)
        return CoreEval(r=r, J=J, dr_domega=dr_dw, dr_dxi=dr_dx, trivial=trivial, d=d, lam=lam,
                        eta=etas, aft=aft, drift=drift, gauge=gauged, state=state)

    def _put(self, out: np.ndarray, h: int, rd: np.ndarray, re: np.ndarray) -> None:
        """Write harmonic ``h``'s complex contact rows ``rd`` and explicit-mode rows ``re`` into the
        real vector ``out`` (real part only for h = 0, ``(a; b)`` slots otherwise)."""
        rows, sl = self._rows(h), self.eta_slices[h]
        if h == 0:
            out[rows], out[sl] = rd.real, re.real
        else:
            out[rows], out[sl] = real_vector(rd), real_vector(re)

    def amplitude2(self, ev: CoreEval, omega: float, xi: float, row: np.ndarray | None = None, h: int = 1):
        """Squared amplitude of harmonic ``h`` and its gradient w.r.t. ``y``, ω and ξ: the modal
        ``Σ_r |η_{h,r}|² = Q_hᴴ M_h Q_h`` (``row`` None), or ``|ρ η_h|² = |w Q_h|²`` of a DoF or
        combination of DoFs ``w`` given as its modal row ``ρ = w Φ_h``. Written ``n² = v·η``-linearised:
        ``δ(n²) = 2 Re(v δη)`` with ``v = η̄`` (modal) or ``v = (ρ η)‾ ρ`` (row), and
        ``δη_C = −(Ψ_Cᴴ δΛ + η_C δz)/z_C`` for the condensed modes."""
        S, Cs = self.S[h], self.Cset[h]
        eta = ev.eta[h]
        n2 = squared_amplitude(eta, row)
        v = np.conj(eta) if row is None else np.conj(row @ eta) * row
        z, dz_dw, dz_dx = self._modal_impedance(h, omega, xi)
        etaC, vC = eta[Cs], v[Cs]
        grad = np.zeros(self.n_core)
        u = self.PsiC[h] @ (np.conj(vC) * np.conj(1.0 / z[Cs]))
        through_contacts = -2.0 * (u.real[None] if h == 0 else real_vector(u)[None])
        grad[:self.n_d] = apply_contact_jacobian(through_contacts, ev.aft.jac, self.fourier.slots(h), self.p)[0]
        vS = np.conj(v[S])
        grad[self.eta_slices[h]] = 2.0 * (vS.real if h == 0 else real_vector(vS))
        weights = np.abs(etaC) ** 2 if row is None else vC * etaC        # v_r η_r
        d_w = -2.0 * _sum_real_product(weights, dz_dw[Cs] / z[Cs])
        d_x = -2.0 * _sum_real_product(weights, dz_dx[Cs] / z[Cs])
        dLam_dw = self._velocity_term(ev.aft)
        if dLam_dw is not None:                    # η_C = (f − Ψ_Cᴴ Λ)/z, Λ depending on ω
            d_w -= 2.0 * _sum_real_product(vC, (self.PsiCH[h] @ dLam_dw[h]) / z[Cs])
        return n2, grad, d_w, d_x

    def _velocity_term(self, aft) -> np.ndarray | None:
        """``∂Λ_h/∂ω`` per harmonic (complex, contact layout) of forces that depend on velocity, or None."""
        if aft.dlam_domega is None:
            return None
        return to_complex(aft.dlam_domega.transpose(2, 0, 1).reshape(self.C, self.p), self.H)

    def _coupled(self, h: int, omega: float, eta_S: np.ndarray) -> np.ndarray | float:
        """Coupling term ``i h ω C_off η_S`` of harmonic ``h``'s explicit rows (0 without coupling)."""
        if self.coupling[h] is None:
            return 0.0
        return 1j * h * omega * (self.coupling[h] @ eta_S)

    def _modal_impedance(self, h, omega, xi):
        m = self.modal[h]
        c = self.damping[h]
        z = m.w2 - (h * omega) ** 2 + 1j * h * omega * (c - xi)
        dz_dw = -2.0 * h * h * omega + 1j * h * (c - xi)
        dz_dx = np.full(m.w2.size, -1j * h * omega)
        return z, dz_dw, dz_dx

    def receptance(self, h: int, omega: float, xi: float, z: np.ndarray) -> np.ndarray:
        """``G_h = Ψ_C diag(1/z_C) Ψ_Cᴴ`` at ``(ω, ξ)`` (``z``: the modal impedances there). Where
        harmonic ``h`` is undamped (and always at h = 0, where ``z_r = ω_r²``), ``z_r = ω_r² − s`` with
        ``s = (hω)² + i hωξ``, and
        :class:`ringdamper.nonlinear.harmonic_balance.receptance.Receptance` sums it; where it has modal
        damping and ``ξ = 0`` (a forced response), ``z_r = ω_r² − u² + i u c_r`` with ``u = hω``, and
        :class:`ringdamper.nonlinear.harmonic_balance.receptance.DampedReceptance` sums it."""
        receptance = self.receptances[h]
        if receptance is not None:
            s = _series_variable(h, omega, xi, isinstance(receptance, DampedReceptance))
            if s is not None:
                return receptance(s)
        Cs = self.Cset[h]
        return (self.PsiC[h] * (1.0 / z[Cs])) @ self.PsiCH[h]

    def explicit_impedance(self, h: int, omega: float, z: np.ndarray) -> np.ndarray:
        """Complex matrix of harmonic ``h``'s explicit rows on ``η_S``: ``diag(z_S)`` plus the
        coupling ``i h ω C_off`` (``z``: the modal impedances at ``omega``)."""
        Z = np.diag(z[self.S[h]])
        return Z if self.coupling[h] is None else Z + 1j * h * omega * self.coupling[h]

    def _rows(self, h: int) -> slice:
        sl = self.fourier.slots(h)
        return slice(sl.start * self.p, sl.stop * self.p)

    def _gauge(self, r, columns, y, kc, state: GaugeState):
        """Replace the rigid-body equilibria along the pinned directions of ``state`` and along
        directions not held by any contact by the gauge ``η_Z = η_ref`` (module docstring), in ``r`` and
        in the Jacobian ``columns`` (ω, ξ); return the dropped equilibria (drift), the gauged
        directions, the :class:`GaugeRotation` the Jacobian's rows take (None if nothing is gauged) and
        the state with the directions found not held added to those seen."""
        nz = self.zero_modes.size
        pinned = state.pinned
        if nz == 0:
            return np.zeros(0), pinned, None, state
        rows = self.eta_slices[0].start + self.zero_modes     # η_Z unknowns and their equilibria
        free = _complement(pinned)
        new = np.zeros((nz, 0))
        if free.shape[1]:
            PsiZ = self.modal[0].Psi[:, self.S[0][self.zero_modes]]       # (p, nz)
            S = np.matmul(kc[..., 0].reshape(self.npairs, -1, 3),
                          PsiZ.reshape(self.npairs, 3, nz)).reshape(-1, nz) @ free
            _, sv, Vt = np.linalg.svd(S, full_matrices=False)
            null = np.r_[sv, np.zeros(free.shape[1] - sv.size)] <= self._null_tol
            if np.any(null) and not np.all(null):
                sign = np.sign(Vt[np.arange(Vt.shape[0]), np.argmax(np.abs(Vt), 1)])
                free = free @ (Vt.T * sign)                            # deterministic basis
            new, free = free[:, null], free[:, ~null]
            state = replace(state, seen=_span(state.seen, new))
        gauge = np.hstack([pinned, new])
        if not gauge.shape[1]:
            return np.zeros(0), gauge, None, state
        rotation = GaugeRotation(rows, np.hstack([free, gauge]), slice(free.shape[1], nz), gauge)
        rot = rotation.V.T @ r[rows]
        drift = rot[rotation.g].copy()
        rot[rotation.g] = gauge.T @ (y[rows] - state.reference)
        r[rows] = rot
        for vec in columns:
            v = rotation.V.T @ vec[rows]
            v[rotation.g] = 0.0
            vec[rows] = v
        return drift, gauge, rotation, state


@dataclass
class GaugeRotation:
    """The rigid-body rows ``rows`` of the Jacobian rotated onto the basis ``V`` (held | gauged
    directions), the gauged ones (``g``) replaced by the gauge ``gauge.T (η_Z − η_ref)``."""

    rows: np.ndarray
    V: np.ndarray
    g: slice
    gauge: np.ndarray

    def apply(self, out: np.ndarray, v: np.ndarray | None = None) -> None:
        """Rotate the rows of ``out`` (the Jacobian, or its product with ``v``) in place."""
        rotated = self.V.T @ out[self.rows]
        rotated[self.g] = 0.0
        if v is None:
            rotated[self.g, self.rows] = self.gauge.T
        else:
            rotated[self.g] = self.gauge.T @ v[self.rows]
        out[self.rows] = rotated


class CoreJacobian:
    """``∂r/∂y`` of one evaluation (module docstring, *Jacobian*): ``I + A_h K_c`` per harmonic plus
    the explicit-mode blocks, with the gauge rows, as an operator (:mod:`ringdamper.nonlinear.solvers.jacobian`).
    :meth:`matvec` is the residual's linearisation applied to a vector (``O(p m)`` per harmonic, the
    receptance ``G_h`` is never formed); :meth:`toarray` forms the matrix (``O(p² m)``) for a
    factorisation."""

    def __init__(self, model: "CondensedHBM", kc: np.ndarray, omega: float, xi: float,
                 rotation: GaugeRotation | None, z: list):
        self.model, self.kc, self.rotation = model, kc, rotation
        self.z = z                                  # the modal impedances of every harmonic at (ω, ξ)
        self.omega, self.xi = omega, xi
        self.shape = (model.n_core, model.n_core)

    def matvec(self, v: np.ndarray) -> np.ndarray:
        m = self.model
        C, p, npairs = m.C, m.p, m.npairs
        vd = v[:m.n_d].reshape(C, p)
        vq = vd.reshape(C, npairs, 3).transpose(1, 2, 0).reshape(npairs, 3 * C, 1)
        dlam = np.matmul(self.kc.reshape(npairs, 3 * C, 3 * C), vq)[..., 0]   # zero blocks: zeros
        dLam = to_complex(dlam.reshape(npairs, 3, C).transpose(2, 0, 1).reshape(C, p), m.H)
        dD = to_complex(vd, m.H)
        out = np.empty(m.n_core)
        for h in range(m.H + 1):
            z, S, Cs = self.z[h], m.S[h], m.Cset[h]
            deta_S = m.eta_explicit(v, h)
            deta_C = -(m.PsiCH[h] @ dLam[h]) / z[Cs]
            m._put(out, h, dD[h] - m.PsiC[h] @ deta_C - m.PsiS[h] @ deta_S,
                   z[S] * deta_S + m._coupled(h, self.omega, deta_S) + m.PsiSH[h] @ dLam[h])
        if self.rotation is not None:
            self.rotation.apply(out, v)
        return out

    def reduced_solver(self, full_order: int, outer=None):
        """The factorised solver on the nonlinear rows of ``outer`` (this Jacobian bordered by a
        continuation; default itself) where the model has its stuck basis and that system is the smaller
        (:func:`ringdamper.nonlinear.harmonic_balance.nonlinear_rows.reduced_solver`), else None."""
        if self.model.stuck is None:
            return None
        return reduced_solver(self.model.stuck, self if outer is None else outer, full_order)

    def toarray(self, out: np.ndarray | None = None) -> np.ndarray:
        """The matrix (Fortran order, :func:`ringdamper.nonlinear.solvers.jacobian.dense`), in ``out`` if
        given (e.g. the core block of a bordered matrix)."""
        m = self.model
        p, kc, n_d = m.p, self.kc, m.n_d
        J = np.empty(self.shape, order="F") if out is None else out
        J[:, n_d:] = 0.0                            # explicit columns: each harmonic sets its own block
        JT = J.T                                    # rows of Jᵀ are contiguous in a Fortran-order J
        for h in range(m.H + 1):
            z, S, sl, rows, PsiS = self.z[h], m.S[h], m.eta_slices[h], m._rows(h), m.PsiS[h]
            G = m.receptance(h, self.omega, self.xi, z)
            slots = m.fourier.slots(h)
            for block, dest in ((G, rows), (m.PsiSH[h], sl)):  # the contact rows, then explicit rows:
                real = block.real if h == 0 else real_block(block)   # each entry of their contact columns
                apply_contact_jacobian(real, kc, slots, p, transposed=True, out=JT[:n_d, dest])
            if h == 0:
                J[rows, sl] = -PsiS.real
                J[sl, sl] = np.diag(z[S].real)
            else:
                J[rows, sl] = -real_block(PsiS)
                J[sl, sl] = real_block(m.explicit_impedance(h, self.omega, z))
        J[np.arange(n_d), np.arange(n_d)] += 1.0
        if self.rotation is not None:
            self.rotation.apply(J)
        return J


def squared_amplitude(eta: np.ndarray, row: np.ndarray | None = None) -> float:
    """``Σ_r |η_r|²`` of the modal coordinates ``eta`` (``Q_hᴴ M_h Q_h``), or ``|ρ η|²`` for a modal
    row ``ρ = w Φ_h`` (the squared amplitude of ``w Q_h``)."""
    return float(np.sum(np.abs(eta) ** 2)) if row is None else float(abs(row @ eta) ** 2)


def _sum_real_product(a: np.ndarray, b: np.ndarray) -> float:
    """``Σ Re(a_k b_k)`` as ``Σ (Re a_k Re b_k − Im a_k Im b_k)`` (a real ``a`` adds exact zeros)."""
    return float(np.sum(a.real * b.real - a.imag * b.imag))


def _split_damping(damping, modal) -> tuple[list, list]:
    """Per harmonic: the modal damping coefficients ``c_r`` (zeros without ``damping``) and the
    off-diagonal coupling (None where ``damping[h]`` is a vector)."""
    diagonal, coupling = [], []
    for h, m in enumerate(modal):
        c = np.zeros(m.w2.size) if damping is None else np.asarray(damping[h])
        if c.ndim == 2:
            diagonal.append(np.real(np.diag(c)).copy())
            coupling.append(c - np.diag(np.diag(c)))
        else:
            diagonal.append(c.astype(float))
            coupling.append(None)
    return diagonal, coupling


def _span(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Orthonormal basis of the span of the columns of ``a`` and ``b`` (at most their row count,
    so lost holds seen at every Newton iterate do not pile up)."""
    merged = np.hstack([a, b])
    if not merged.shape[1]:
        return merged
    u, sv, _ = np.linalg.svd(merged, full_matrices=False)
    return u[:, :int(np.sum(sv > 1e-8 * sv[0]))]


def _complement(basis: np.ndarray) -> np.ndarray:
    """Orthonormal basis of the orthogonal complement of the orthonormal columns ``basis``
    (the identity when there are none)."""
    n, k = basis.shape
    if k == 0:
        return np.eye(n)
    u, _, _ = np.linalg.svd(basis, full_matrices=True)
    return u[:, k:]


def _series_variable(h: int, omega: float, xi: float, damped: bool):
    """The variable of harmonic ``h``'s receptance series at ``(ω, ξ)`` (:meth:`CondensedHBM.receptance`):
    ``s = (hω)² + i hωξ`` (0 at h = 0) for the undamped series, ``u = hω`` for the damped one (``damped``),
    which serves ``ξ = 0`` only (None otherwise)."""
    if damped:
        return h * omega if xi == 0.0 else None
    return h * h * omega * omega + 1j * h * omega * xi if h else 0.0


def _receptance(h: int, w2: np.ndarray, c: np.ndarray, Psi: np.ndarray, PsiH: np.ndarray, coupled: bool,
                expansion: tuple[float, float] | None):
    """The summation of harmonic ``h``'s condensed receptance (:meth:`CondensedHBM.receptance`), its series
    formed about ``expansion = (ω, ξ)`` (:func:`_series_variable`): the undamped series at h = 0 and on
    undamped harmonics, the damped one on modally damped harmonics (where ``ξ = 0`` there: the series serves
    ξ = 0 only); none (the direct sum) where the damping couples the modes, or without ``expansion``."""
    if expansion is None:
        return None
    if h == 0 or not np.any(c):
        return Receptance(w2, Psi, PsiH, _series_variable(h, *expansion, damped=False))
    u0 = None if coupled else _series_variable(h, *expansion, damped=True)
    return None if u0 is None else DampedReceptance(w2, c, Psi, PsiH, u0)


def pole_modes(structure: Structure, H: int, lo: float, hi: float) -> list:
    """Explicit-mode sets: for ``h ≥ 1`` the modes with ``ω_r ∈ [h·lo, h·hi]`` (none if
    ``hi ≤ lo``); harmonic 0 gets its zero modes automatically in :class:`CondensedHBM`."""
    out = [np.zeros(0, int)]
    for h in range(1, H + 1):
        w = np.sqrt(structure.modal(h).w2)
        out.append(np.flatnonzero((w >= h * lo) & (w <= h * hi)) if hi > lo else np.zeros(0, int))
    return out


def apply_contact_jacobian(A: np.ndarray, kc: np.ndarray, slots: slice, p: int, transposed: bool = False,
                            out: np.ndarray | None = None) -> np.ndarray:
    """``A @ K_c[slots rows, :]`` with ``A`` (R, L·p) over ``(slot in slots, coordinate)`` columns
    and ``K_c`` the block-diagonal AFT Jacobian ``kc`` (np, 3, C, 3, C), one small product per pair over
    views of ``A`` and ``kc`` (a pair without contact stiffness has a zero block and gives zeros: picking
    out the others would copy ``A``, which costs more than their products).
    ``transposed``: the product's transpose (C·p, R) instead, computed as such (``K_cᵀ Aᵀ`` pair by
    pair), for the rows of a transposed matrix. ``out``: where to write the product (e.g. a view of a
    larger matrix; every entry is set), else a new array."""
    npairs, C = kc.shape[0], kc.shape[2]
    L = slots.stop - slots.start
    R = A.shape[0]
    result = np.empty((C * p, R) if transposed else (R, C * p)) if out is None else out
    out = result.reshape((C, npairs, 3, R) if transposed else (R, C, npairs, 3))   # splits one axis: a view
    Aq = A.reshape(R, L, npairs, 3)
    Kq = kc[:, :, slots].transpose(0, 2, 1, 3, 4).reshape(npairs, 3 * L, 3 * C)
    if transposed:
        product = np.matmul(Kq.transpose(0, 2, 1), Aq.transpose(2, 1, 3, 0).reshape(npairs, 3 * L, R))
        out[:] = product.reshape(npairs, 3, C, R).transpose(2, 0, 1, 3)
    else:
        product = np.matmul(Aq.transpose(2, 0, 1, 3).reshape(npairs, R, 3 * L), Kq)
        out[:] = product.reshape(npairs, R, 3, C).transpose(1, 3, 0, 2)
    return result
