"""The linear structure seen by the harmonic balance: one matrix set per harmonic (docs/design.md §3.3–3.4).

Harmonic ``h`` of the reference sector obeys ``(K_h − h²ω² M_h + ihω C_h) Q_h + B_hᴴ Λ_h = F_h``
(Galerkin projection, Hermitian ``M_h``, ``K_h``), where ``d_h = B_h Q_h`` are the harmonics of the
stacked relative contact coordinates ``[d_n, d_t1, d_t2]`` of every pair. For a cyclic structure of
``N`` sectors excited by engine order ``EO`` (travelling wave), harmonic ``h`` of sector ``j`` is
harmonic ``h`` of the reference sector times ``e^{iσ_h j}``, ``σ_h = −2π h EO / N`` (nodal diameter
``h·EO mod N``), so ``(M_h, K_h, B_h)`` are the sector matrices under ``u_{j+1} = e^{iσ_h} u_j``.
Harmonic 0 is ND 0 and real. A non-cyclic structure uses the same real matrices for every ``h``.

Each harmonic is diagonalised once (``K_h φ = ω_r² M_h φ``, ``φᴴ M_h φ = 1``, all modes): this is
what the exact condensation of :mod:`ringdamper.nonlinear.harmonic_balance.condensed` sums over.

Structural damping is given per harmonic either as a viscous matrix ``C_h`` or as modal damping
ratios ``ζ_r`` of the modes of ``(K_h, M_h)`` (``C_h = M_h Φ diag(2 ζ_r ω_r) Φᴴ M_h``); either gives the
modal damping ``Φᴴ C_h Φ``. Its diagonal, the coefficients ``c_r = φ_rᴴ C_h φ_r``, is what the modal
receptances use (:meth:`ModalHarmonic.damping`). A ``C_h`` that is *not* diagonal in the modes
(``φ_rᴴ C_h φ_s ≠ 0`` for some ``r ≠ s``, relative to the largest modal entry above
:data:`COUPLING_TOL`: a dashpot on one DoF, damping non-proportional to ``(K, M)``) couples the modes;
its off-diagonal part is kept as ``ModalHarmonic.coupling`` and the analyses then keep every mode of
that harmonic as an unknown instead of condensing it (:mod:`ringdamper.nonlinear.harmonic_balance.condensed`), exact
and meant for the small systems where such damping is given.
Every matrix and vector is checked at construction: the message names the argument, the shape
expected and the shape given.
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from typing import Callable, Sequence

import numpy as np
import scipy.linalg as sla

from ringdamper.fem.cyclic import interblade_phase

#: off-diagonal modal damping below this fraction of the largest modal entry counts as modal (dropped)
COUPLING_TOL = 1e-8


@dataclass
class HarmonicData:
    """Linear data of one harmonic: ``M``, ``K`` (n × n, Hermitian), ``B`` (p × n, contact relative
    coordinates), ``response`` (n,) row giving the response DoF, ``force`` (n,) forcing vector
    (None: unforced), and optionally the structural damping: ``C`` (n × n) or ``zeta``, modal
    damping ratios of the modes of ``(K, M)`` (scalar or one per mode, ascending frequency), not
    both."""

    M: np.ndarray
    K: np.ndarray
    B: np.ndarray
    response: np.ndarray
    force: np.ndarray | None = None
    C: np.ndarray | None = None
    zeta: float | np.ndarray | None = None

    def check(self, name: str) -> None:
        """Shapes and values of every field against ``n`` = rows of ``M``; ``ValueError`` naming
        ``name.field``, the shape expected and the shape given."""
        n = np.shape(self.M)[0] if np.ndim(self.M) == 2 else None
        if n is None or np.shape(self.M) != (n, n):
            raise ValueError(f"{name}.M: expected a square matrix (n, n), got shape {np.shape(self.M)}")
        expected = {"K": (n, n), "response": (n,), "force": (n,), "C": (n, n)}
        for field_name, shape in expected.items():
            value = getattr(self, field_name)
            if value is not None and np.shape(value) != shape:
                raise ValueError(f"{name}.{field_name}: expected shape {shape} (n = {n} DoFs, from M), "
                                 f"got {np.shape(value)}")
        if np.ndim(self.B) != 2 or np.shape(self.B)[1] != n:
            raise ValueError(f"{name}.B: expected shape (p, {n}) (p contact coordinates, n = {n} DoFs), "
                             f"got {np.shape(self.B)}")
        if self.C is not None and self.zeta is not None:
            raise ValueError(f"{name}: give the damping as C or as modal ratios zeta, not both")
        if self.zeta is not None:
            if np.shape(self.zeta) not in ((), (n,)):
                raise ValueError(f"{name}.zeta: expected a scalar or shape ({n},) (one ratio per mode), "
                                 f"got {np.shape(self.zeta)}")
            if np.any(np.asarray(self.zeta, float) < 0):
                raise ValueError(f"{name}.zeta: modal damping ratios must be >= 0")


@dataclass
class ModalHarmonic:
    """Modes of one harmonic: ``w2`` (ω_r², zero modes set to exactly 0), ``Phi`` (n × m,
    mass-normalised), ``Psi = B Phi`` (p × m), modal force ``f = Phiᴴ force``, modal response row
    ``res = response Phi``, modal damping ``c = diag(Phiᴴ C Phi)`` (None without ``C``), its
    off-diagonal part ``coupling`` (m × m, None when ``C`` is diagonal in the modes) and the
    boolean mask ``zero`` of zero-frequency (rigid-body) modes."""

    h: int
    w2: np.ndarray
    Phi: np.ndarray
    Psi: np.ndarray
    f: np.ndarray
    res: np.ndarray
    c: np.ndarray | None
    zero: np.ndarray = field(repr=False)
    coupling: np.ndarray | None = field(default=None, repr=False)

    def damping(self, zeta_s: float | np.ndarray = 0.0) -> np.ndarray:
        """Modal damping coefficients ``c_r`` (``q̇`` term ``c_r η̇_r``): the structure's (``C`` or
        modal ratios) if it has them, else ``2 ζ_s ω_r`` (modal damping ratio ζ_s, scalar or per
        mode). A structure with its own damping and a non-zero ``zeta_s`` is ambiguous: raises."""
        if self.c is not None:
            if np.any(np.asarray(zeta_s) != 0):
                raise ValueError("zeta_s: the structure has its own damping (C or modal ratios); "
                                 "give one of the two, not both")
            return self.c
        return 2.0 * np.asarray(zeta_s, float) * np.sqrt(self.w2)


class Structure:
    """Per-harmonic linear structure for harmonics ``0..H_max`` (``harmonics[h]``)."""

    def __init__(self, harmonics: Sequence[HarmonicData], zero_tol: float = 1e-9,
                 n_sectors: int | None = None, engine_order: int | None = None):
        self.harmonics = list(harmonics)
        self.zero_tol = zero_tol
        self.n_sectors, self.engine_order = n_sectors, engine_order
        for h, hd in enumerate(self.harmonics):
            hd.check(f"harmonic {h}")
        p = {hd.B.shape[0] for hd in self.harmonics}
        if len(p) != 1:
            raise ValueError(f"B: every harmonic must map onto the same contact coordinates, got "
                             f"{[hd.B.shape[0] for hd in self.harmonics]} rows")
        self.p = p.pop()
        if self.p % 3:
            raise ValueError(f"B: expected 3 rows (n, t1, t2) per contact pair, got {self.p} rows")
        h0 = self.harmonics[0]
        if any(np.iscomplexobj(a) and np.any(np.abs(np.imag(a)) > 0)
               for a in (h0.M, h0.K, h0.B)):
            raise ValueError("harmonic 0 (ND 0) matrices must be real")
        self._eig_cache: dict = {}
        self._modal_cache: dict[int, ModalHarmonic] = {}

    @property
    def H_max(self) -> int:
        return len(self.harmonics) - 1

    @property
    def npairs(self) -> int:
        return self.p // 3

    @property
    def damped(self) -> bool:
        """The structure carries its own damping (``C`` or modal ratios) in some harmonic."""
        return any(hd.C is not None or hd.zeta is not None for hd in self.harmonics)

    def damping_matrix(self, h: int) -> np.ndarray | None:
        """Viscous damping matrix of harmonic ``h``: ``C`` as given, or from the modal ratios
        ``C = M Φ diag(2 ζ_r ω_r) Φᴴ M`` (None if undamped)."""
        hd = self.harmonics[h]
        if hd.zeta is None:
            return hd.C
        m = self.modal(h)
        MPhi = hd.M @ m.Phi
        return (MPhi * m.c) @ MPhi.conj().T

    def with_response(self, response: np.ndarray) -> "Structure":
        """The same structure observed through another response row: ``response`` (n,), any DoF
        (a unit row) or linear combination of DoFs, for every harmonic, or one row per harmonic
        ``(H_max + 1, n)``. Results report ``response · Q_h`` (``q_res_h1``, ``q_h1``, the peaks); the
        modes are shared, not computed again."""
        rows = np.asarray(response)
        rows = np.broadcast_to(rows, (len(self.harmonics),) + rows.shape) if rows.ndim == 1 else rows
        if rows.ndim != 2 or rows.shape[0] != len(self.harmonics):
            raise ValueError(f"response: expected shape (n,) or ({len(self.harmonics)}, n), got {np.shape(response)}")
        data = [dataclasses.replace(hd, response=np.array(r)) for hd, r in zip(self.harmonics, rows)]
        out = Structure(data, zero_tol=self.zero_tol, n_sectors=self.n_sectors, engine_order=self.engine_order)
        out._eig_cache = self._eig_cache
        return out

    @classmethod
    def real(cls, M, K, B, response, force, H: int, C=None, zeta=None,
             zero_tol: float = 1e-9) -> "Structure":
        """Non-cyclic structure: the same real matrices for every harmonic, ``force`` on
        harmonic 1 only; damping ``C`` or modal ratios ``zeta`` (module docstring)."""
        n = np.shape(M)[0] if np.ndim(M) == 2 else 0
        zero = np.zeros(n)
        data = [HarmonicData(M, K, B, response, zero if h != 1 else force, C, zeta) for h in range(H + 1)]
        return cls(data, zero_tol=zero_tol)

    @classmethod
    def cyclic(cls, n_sectors: int, engine_order: int, H: int,
               sector: Callable[[int, float], HarmonicData], zero_tol: float = 1e-9) -> "Structure":
        """Cyclic travelling-wave structure: ``sector(h, σ_h)`` returns the reference-sector data
        of harmonic ``h`` under ``u_{j+1} = e^{iσ_h} u_j``, ``σ_h`` from :func:`interblade_phase`."""
        data = [sector(h, interblade_phase(h, n_sectors, engine_order)) for h in range(H + 1)]
        return cls(data, zero_tol=zero_tol, n_sectors=n_sectors, engine_order=engine_order)

    def modal(self, h: int) -> ModalHarmonic:
        """Modal decomposition of harmonic ``h`` (cached; matrices shared between harmonics are
        diagonalised once)."""
        if h in self._modal_cache:
            return self._modal_cache[h]
        hd = self.harmonics[h]
        key = (id(hd.K), id(hd.M))
        if key not in self._eig_cache:
            self._eig_cache[key] = _mass_normalised_modes(hd.K, hd.M, real=(h == 0))
        w2, Phi = self._eig_cache[key]
        zero = w2 <= self.zero_tol * max(np.max(np.abs(w2)), np.finfo(float).tiny)
        w2 = np.where(zero, 0.0, w2)
        if h > 0 and np.any(w2 < 0):
            raise ValueError(f"harmonic {h}: K_h is not positive semi-definite")
        f = Phi.conj().T @ hd.force if hd.force is not None else np.zeros(Phi.shape[1], complex)
        c = coupling = None
        if hd.zeta is not None:
            c = 2.0 * np.broadcast_to(np.asarray(hd.zeta, float), w2.shape) * np.sqrt(w2)
        elif hd.C is not None:
            c, coupling = _modal_damping(Phi, hd.C)
        mh = ModalHarmonic(h=h, w2=w2, Phi=Phi, Psi=hd.B @ Phi, f=f, res=hd.response @ Phi,
                           c=c, zero=zero, coupling=coupling)
        if h == 0:
            mh.Psi, mh.f, mh.res = mh.Psi.real, mh.f.real, mh.res.real
            mh.coupling = None if coupling is None else coupling.real
        self._modal_cache[h] = mh
        return mh

    def stuck_modes(self, stiffness: np.ndarray, h: int = 1):
        """Modes of harmonic ``h`` with linear contact springs ``stiffness`` (p,) added, i.e. the
        linearised stuck system ``K_h + B_hᴴ diag(k) B_h``: returns ``(ω, Φ)``, ω ascending (cached
        per harmonic and stiffness, read-only: the stage asks for them twice, for the target mode
        and for the start of the continuation)."""
        hd = self.harmonics[h]
        stiffness = np.asarray(stiffness, float)
        key = ("stuck", id(hd.K), id(hd.M), id(hd.B), stiffness.tobytes())
        if key not in self._eig_cache:
            K = hd.K + hd.B.conj().T @ (stiffness[:, None] * hd.B)
            w2, Phi = _mass_normalised_modes(K, hd.M, real=(h == 0))
            modes = np.sqrt(np.maximum(w2, 0.0)), Phi
            for a in modes:
                a.setflags(write=False)
            self._eig_cache[key] = modes
        return self._eig_cache[key]


def _modal_damping(Phi: np.ndarray, C: np.ndarray):
    """``(c, coupling)`` of the modal damping ``Φᴴ C Φ``: its real diagonal and its off-diagonal
    part (None when that is below :data:`COUPLING_TOL` of the largest modal entry)."""
    Cm = Phi.conj().T @ C @ Phi
    diagonal = np.diag(Cm)
    off = Cm - np.diag(diagonal)
    scale = max(np.max(np.abs(Cm)), np.finfo(float).tiny)
    return np.real(diagonal), (off if np.max(np.abs(off)) > COUPLING_TOL * scale else None)


def _mass_normalised_modes(K, M, real: bool):
    """Eigenpairs of ``K φ = ω² M φ`` (Hermitian parts), ``φᴴ M φ = 1``, ω² ascending. A diagonal
    pencil (a structure given in its own modes, as the campaign's reduced.nc) is solved as such:
    ``ω² = K_ii / M_ii``, ``φ = e_i / √M_ii``, which LAPACK returns too, bit for bit, in 30 ms a
    harmonic at 543 modes."""
    K = 0.5 * (K + K.conj().T)
    M = 0.5 * (M + M.conj().T)
    if real:
        K, M = np.real(K), np.real(M)
    k, m = np.diag(K), np.diag(M)
    if np.count_nonzero(K - np.diag(k)) == 0 and np.count_nonzero(M - np.diag(m)) == 0 \
            and np.all(m.real > 0):
        w2 = (k / m).real
        order = np.argsort(w2, kind="stable")
        Phi = np.zeros(K.shape, dtype=np.result_type(K, M))
        Phi[order, np.arange(order.size)] = 1.0 / np.sqrt(m.real[order])
        return w2[order], Phi
    w2, Phi = sla.eigh(K, M)
    return w2, Phi
