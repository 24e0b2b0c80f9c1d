"""Newton systems of the condensed HBM solved on its nonlinear contact rows only.

The contact tangent ``K_c`` of :class:`ringdamper.nonlinear.harmonic_balance.condensed.CoreJacobian`
is written as the stuck springs ``D`` (``(kn, kt, kt)`` of every preloaded pair, the same in every
harmonic slot: what the AFT returns for a pair that sticks and stays closed all period) plus
``ΔK = K_c − D``, which vanishes on every *linear* row: all rows of a pair that sticks, and the normal
rows of a pair that stays closed while it slips. A row is linear where its entries of ``ΔK`` are below
:data:`LINEAR_TOL` of the contact stiffness scale (the AFT's ``F E = I`` leaves rounding there).

Per harmonic ``h`` (undamped harmonics; ``s = (hω)² + i hωξ``) the core Newton system ``J δy = b`` is
the exact condensation of the modal system over all modes ``η`` of the free structure,

    (diag(ω_r² − s) + Ψᴴ D Ψ) δη + Ψᴴ ΔΛ = [0; b_S] − Ψᴴ D b_d,   δd = Ψ δη + b_d,   ΔΛ = ΔK δd,

(``b_d``: contact rows, ``b_S``: explicit-mode rows of ``b``). In the modes of the stuck structure,
``diag(ω_r²) + Ψᴴ D Ψ = T diag(ω̃_r²) Tᴴ`` (:class:`StuckBasis`, ``T`` unitary, ``Ψ̃ = Ψ T``), with
``δη = T δη̃``:

    (ω̃_r² − s) δη̃_r + ψ̃_rᴴ ΔΛ = g_r,     g = T_Sᴴ b_S − Ψ̃ᴴ D b_d,     δd = Ψ̃ δη̃ + b_d.

The stuck modes far from ``hω`` are eliminated, ``δη̃_r = (g_r − ψ̃_rᴴ ΔΛ) / (ω̃_r² − s)``; the resonant
ones (``|ω̃_r² − (hω)²| ≤`` :data:`RESONANT_BAND` ``(hω)²``) stay unknowns ``e``, so the receptance
never passes a pole. What remains has the unknowns ``w = ΔΛ`` on the nonlinear rows ``R``, ``e``, the
gauge forces ``μ`` and the continuation's bordering unknowns ``t``, with the equations

    w = ΔK_R δd(w, e, μ, t),   (ω̃_ρ² − s) e + Ψ̃_ρᴴ w = g_ρ,   Gᵀ δη_Z = β,   (bordering rows),

the Woodbury (capacitance) form of ``J = J_D + (J − J_D)``: its order is ``|R| + |ρ| + n_g + k``, not the
``3 · pairs · (2H + 1)`` of the full system. The gauge (module docstring of
:mod:`ringdamper.nonlinear.harmonic_balance.condensed`): the rotated rigid-body rows are the held
equilibria ``V_fᵀ(Ψ_Zᵀ K_c δd) = b_f`` and the gauge ``Gᵀ δη_Z = β``; written unrotated, the equilibria
take a force ``G μ`` along the gauged directions (``μ``: the stop's force) and the gauge is one more
equation. ``ΔK`` couples the harmonics (the AFT), so ``w`` is kept in real slots; the modal parts are
complex per harmonic.
"""
from __future__ import annotations

import numpy as np
import scipy.linalg as sla

from ringdamper.nonlinear.fourier import real_block, to_complex, to_real
from ringdamper.nonlinear.harmonic_balance.receptance import Receptance
from ringdamper.nonlinear.solvers.budget import charge_lu
from ringdamper.nonlinear.solvers.jacobian import Bordered, apply

#: a contact row is linear where its entries of ``K_c − D`` are below this fraction of the stiffness scale
LINEAR_TOL = 1e-12
#: the reduced system replaces the full LU where its order is at most this fraction of the full order
#: (on the default ring, a factorisation and a solve: 2.3× faster at 0.34, 1.5× at 0.45–0.5, slower at 0.8)
ORDER_RATIO = 0.6
#: stuck modes with ``|ω̃_r² − (hω)²|`` within this fraction of ``(hω)²`` stay unknowns (at h = 0: ``ω̃_r ≈ 0``)
RESONANT_BAND = 0.75


class StuckBasis:
    """The stuck structure of a :class:`ringdamper.nonlinear.harmonic_balance.condensed.CondensedHBM`:
    per harmonic, ``diag(ω_r²) + Ψ_hᴴ diag(k) Ψ_h = T_h diag(ω̃²_h) T_hᴴ`` over the model's modes
    (``k``: the stuck springs, (p,)), ``Ψ̃_h = Ψ_h T_h`` and ``T_{S,h} = T_h[S_h]`` (the explicit modes'
    rows). Its receptances at the contact: at h = 0 the static one over the modes not at zero frequency
    (``ω̃² > 1e-8 max ω̃²``; the others stay unknowns), for h ≥ 1 a
    :class:`ringdamper.nonlinear.harmonic_balance.receptance.Receptance` whose far modes' series is formed
    about ``s₀ = (hω₀)²`` (``omega0``; None: direct sums). Fixed along a branch; built once per model.
    Undamped models only (the modal damping is not diagonal in the stuck modes)."""

    def __init__(self, model, stiffness: np.ndarray, omega0: float | None = None):
        if model.damped:
            raise ValueError("nonlinear-rows solve: the model carries structural damping, which the stuck "
                             "modes do not diagonalise; use the full Newton system")
        self.model = model
        self.k = np.asarray(stiffness, float).ravel()
        if self.k.size != model.p:
            raise ValueError(f"stiffness: expected {model.p} springs (3 per pair), got {self.k.size}")
        self.w2, self.Psi, self.PsiH, self.T_S, self.receptances = [], [], [], [], []
        for h, m in enumerate(model.modal):
            A = np.diag(m.w2) + m.Psi.conj().T @ (self.k[:, None] * m.Psi)
            w2, T = sla.eigh(A.real if h == 0 else A)
            Psi = m.Psi @ T
            self.w2.append(w2)
            self.Psi.append(Psi)
            self.PsiH.append(Psi.conj().T.copy())
            self.T_S.append(T[model.S[h]])
            if h == 0:
                self.rigid = w2 <= 1e-8 * np.max(np.abs(w2))
                held = ~self.rigid
                self.receptances.append((Psi[:, held] / w2[held]) @ Psi[:, held].T)
            else:
                self.receptances.append(None if omega0 is None else
                                        Receptance(w2, Psi, self.PsiH[h], (h * omega0) ** 2))


def _flatten(J):
    """``(core, columns, rows)`` of a core Jacobian bordered (once or more, :class:`Bordered`) by
    ``columns`` (n_core × k) and ``rows`` (k × (n_core + k))."""
    if not isinstance(J, Bordered):
        n = J.shape[0]
        return J, np.zeros((n, 0)), np.zeros((0, n))
    core, columns, rows = _flatten(J.A)
    n = core.shape[0]
    columns = np.hstack([columns, J.columns[:n]])
    rows = np.vstack([np.hstack([rows, J.columns[n:]]), J.rows])
    return core, columns, rows


def reduced_solver(basis: StuckBasis, J, full_order: int) -> "NonlinearRowsSolver | None":
    """The factorised :class:`NonlinearRowsSolver` of ``J`` where its order is below :data:`ORDER_RATIO`
    of ``full_order`` (the full LU's, trivial unknowns eliminated), else None (the full LU is cheaper)."""
    solver = NonlinearRowsSolver(basis, J)
    return solver.factorize() if solver.order <= ORDER_RATIO * full_order else None


class NonlinearRowsSolver:
    """Solver of ``J x = b`` for a :class:`ringdamper.nonlinear.harmonic_balance.condensed.CoreJacobian`
    ``J`` (or one bordered by a continuation) through the reduced system of the module docstring, of
    order :attr:`order` (known once built; :meth:`factorize` forms and factorises it); ``basis``: the
    model's :class:`StuckBasis`."""

    def __init__(self, basis: StuckBasis, J):
        self.basis, self.J = basis, J
        self.core, self.columns, self.rows = _flatten(J)
        model = self.model = basis.model
        if self.core.model is not model:
            raise ValueError("the Jacobian belongs to another model than the stuck basis")
        self.n = self.core.shape[0] + self.columns.shape[1]
        self._classify_rows()
        self._split_modes()
        rotation = self.core.rotation
        self.ng = 0 if rotation is None else rotation.gauge.shape[1]
        self.sizes = (self.R.size, sum(self._e_size(h) for h in range(model.H + 1)), self.ng,
                      self.columns.shape[1])
        self.order = sum(self.sizes)
        self.lu = None

    def factorize(self) -> "NonlinearRowsSolver":
        """Form the reduced matrix, equilibrated, and its LU (charged to an open
        :func:`ringdamper.nonlinear.solvers.budget.lu_budget`); returns itself."""
        charge_lu("nonlinear_rows")
        A = self._matrix()
        self.row_scale = 1.0 / np.maximum(np.max(np.abs(A), axis=1), np.finfo(float).tiny)
        A *= self.row_scale[:, None]
        self.col_scale = 1.0 / np.maximum(np.max(np.abs(A), axis=0), np.finfo(float).tiny)
        A *= self.col_scale
        self.lu = sla.lu_factor(A, check_finite=False, overwrite_a=True)
        return self

    @property
    def factorization(self) -> "NonlinearRowsSolver":
        return self

    # ---- the reduced unknowns ------------------------------------------------------------------
    def _classify_rows(self) -> None:
        """The nonlinear rows ``R`` (real contact-slot indices) and ``ΔK`` per pair (zero on linear rows)."""
        m, kc = self.model, self.core.kc
        npairs, C = m.npairs, m.C
        D = np.zeros_like(kc)
        k = self.basis.k.reshape(npairs, 3)
        for i in range(3):
            D[:, i, np.arange(C), i, np.arange(C)] = k[:, i, None]
        dK = kc - D
        scale = m.contacts.stiffness_scale()
        nonlinear = np.max(np.abs(dK).reshape(npairs, 3, C, -1), axis=-1) > LINEAR_TOL * scale
        dK[~nonlinear] = 0.0
        self.dK = dK.reshape(npairs, 3 * C, 3 * C)
        # real slot index of (pair q, direction i, slot c) is c·p + 3q + i
        q, i, c = np.nonzero(nonlinear)
        self.R = np.sort(c * m.p + 3 * q + i)
        self.pairs = np.flatnonzero(nonlinear.any(axis=(1, 2)))
        self.coords = np.unique(self.R % m.p)

    def _split_modes(self) -> None:
        """Per harmonic the resonant stuck modes ``ρ`` (unknowns) and the others ``φ`` (eliminated), and
        the stuck impedances ``ω̃² − s``."""
        omega, xi = self.core.omega, self.core.xi
        self.rho, self.phi, self.zt = [], [], []
        for h, w2 in enumerate(self.basis.w2):
            u2 = (h * omega) ** 2
            near = self.basis.rigid if h == 0 else np.abs(w2 - u2) <= RESONANT_BAND * u2
            self.rho.append(np.flatnonzero(near))
            self.phi.append(np.flatnonzero(~near))
            self.zt.append(w2 - u2 - 1j * h * omega * xi)

    def _e_size(self, h: int) -> int:
        return self.rho[h].size * (1 if h == 0 else 2)

    def _split(self, u: np.ndarray):
        """``(w, e per harmonic (complex), μ, t)`` of reduced unknowns ``u`` (order × q)."""
        nR, ne, ng, _ = self.sizes
        w, rest = u[:nR], u[nR:]
        e = []
        for h in range(self.model.H + 1):
            size = self._e_size(h)
            block, rest = rest[:size], rest[size:]
            e.append(block.astype(complex) if h == 0 else block[:size // 2] - 1j * block[size // 2:])
        return w, e, rest[:ng], rest[ng:]

    # ---- the reduced equations -----------------------------------------------------------------
    def _lift(self, b, w, e, mu, harmonics):
        """The core unknowns ``δy`` (n_core × q) of the core right-hand sides ``b`` (n_core × q, the
        bordering's ``−c t`` included; None: zero) and the reduced unknowns ``w``, ``e``, ``μ``, computed
        on ``harmonics`` (zero on the others); and what the reduced equations read: per harmonic the
        resonant rows' ``g_ρ − Ψ̃_ρᴴ ΔΛ``, the zero modes' ``δη_Z`` and the gauge's ``β``."""
        m, bs = self.model, self.basis
        q = w.shape[1]
        lam = np.zeros((m.n_d, q))
        lam[self.R] = w
        Lam = to_complex(lam.reshape(m.C, m.p, q), m.H)
        Bd = None if b is None else to_complex(b[:m.n_d].reshape(m.C, m.p, q), m.H)
        X = np.zeros((m.H + 1, m.p, q), complex)
        dy = np.zeros((m.n_core, q))
        resonant, eta_Z, beta = [None] * (m.H + 1), np.zeros((0, q)), np.zeros((self.ng, q))
        loaded = np.any(w) or (self.ng and np.any(mu))
        for h in harmonics:
            bS, beta_h = self._explicit_rhs(b, h, q)
            if beta_h is not None:
                beta = beta_h
            phi, rho = self.phi[h], self.rho[h]
            eta = np.zeros((bs.w2[h].size, q), complex)
            eta[rho] = e[h]
            resonant[h] = np.zeros((rho.size, q), complex)
            if b is not None or loaded:              # the eliminated stuck modes move (else only ρ does)
                load = -(bs.PsiH[h][:, self.coords] @ Lam[h][self.coords])         # g − Ψ̃ᴴ ΔΛ
                if b is not None:
                    load += bs.T_S[h].conj().T @ bS - bs.PsiH[h] @ (bs.k[:, None] * Bd[h])
                if h == 0 and self.ng:
                    load += bs.T_S[0][m.zero_modes].T @ (self.core.rotation.gauge @ mu)
                eta[phi] = load[phi] / self.zt[h][phi, None]
                resonant[h] = load[rho]
                X[h] = bs.Psi[h] @ eta + (0.0 if Bd is None else Bd[h])
                deta = bs.T_S[h] @ eta
            else:
                X[h] = bs.Psi[h][:, rho] @ e[h]
                deta = bs.T_S[h][:, rho] @ e[h]
            dy[m.eta_slices[h]] = deta.real if h == 0 else np.vstack([deta.real, -deta.imag])
            if h == 0:
                eta_Z = deta.real[m.zero_modes]
        dy[:m.n_d] = to_real(X).reshape(m.n_d, q)
        return dy, resonant, eta_Z, beta

    def _explicit_rhs(self, b, h: int, q: int):
        """Harmonic ``h``'s explicit-mode rows of ``b`` (complex) and, at h = 0 with a gauge, ``β``: the
        rotated rigid-body rows unrotated onto the held equilibria (module docstring)."""
        m = self.model
        if b is None:
            return None, None
        v = b[m.eta_slices[h]]
        if h:
            s = v.shape[0] // 2
            return v[:s] - 1j * v[s:], None
        v = v.astype(complex)
        rotation = self.core.rotation
        if rotation is None:
            return v, None
        rotated = v[m.zero_modes].real
        nf = rotation.g.start
        v[m.zero_modes] = rotation.V[:, :nf] @ rotated[:nf]
        return v, rotated[rotation.g]

    def _equations(self, b, u, b_ext, harmonics):
        """The reduced equations' residuals (order × q) at core right-hand sides ``b`` (None: zero),
        bordering right-hand sides ``b_ext`` (None: zero) and reduced unknowns ``u``."""
        m = self.model
        w, e, mu, t = self._split(u)
        if self.columns.shape[1]:
            ct = -(self.columns @ t)
            b = ct if b is None else b + ct
        dy, resonant, eta_Z, beta = self._lift(b, w, e, mu, harmonics)
        parts = [w - self._apply_dK(dy[:m.n_d])]
        for h in range(m.H + 1):
            if h in harmonics:
                r = self.zt[h][self.rho[h], None] * e[h] - resonant[h]
            else:
                r = np.zeros((self.rho[h].size, u.shape[1]), complex)
            parts.append(r.real if h == 0 else np.vstack([r.real, -r.imag]))
        if self.ng:
            parts.append(self.core.rotation.gauge.T @ eta_Z - beta if 0 in harmonics
                         else np.zeros((self.ng, u.shape[1])))
        border = self.rows[:, :m.n_core] @ dy + self.rows[:, m.n_core:] @ t
        parts.append(border if b_ext is None else border - b_ext)
        return np.vstack(parts)

    def _apply_dK(self, dx: np.ndarray) -> np.ndarray:
        """``(ΔK dx)[R]`` for contact slots ``dx`` (n_d × q), pair by pair (pairs with a nonlinear row)."""
        m = self.model
        q = dx.shape[1]
        vq = dx.reshape(m.C, m.npairs, 3, q).transpose(1, 2, 0, 3)[self.pairs].reshape(-1, 3 * m.C, q)
        out = np.zeros((m.npairs, 3, m.C, q))
        out[self.pairs] = np.matmul(self.dK[self.pairs], vq).reshape(-1, 3, m.C, q)
        return out.transpose(2, 0, 1, 3).reshape(m.n_d, q)[self.R]

    def _matrix(self) -> np.ndarray:
        """The reduced matrix, block by block of unknowns (each harmonic's ``w`` and ``e`` touch only
        that harmonic's modes)."""
        m = self.model
        A = np.empty((self.order, self.order))
        harmonic_of_row = (self.R // m.p + 1) // 2
        blocks = [(np.flatnonzero(harmonic_of_row == h), [h]) for h in range(m.H + 1)]
        start = self.R.size
        for h in range(m.H + 1):
            blocks.append((np.arange(start, start + self._e_size(h)), [h]))
            start += self._e_size(h)
        blocks.append((np.arange(start, start + self.ng), [0]))
        start += self.ng
        blocks.append((np.arange(start, self.order), list(range(m.H + 1))))
        for h, (columns, harmonics) in enumerate(blocks):
            if not columns.size:
                continue
            if h <= m.H:
                A[:, columns] = self._w_columns(h, columns)
                continue
            unit = np.zeros((self.order, columns.size))
            unit[columns, np.arange(columns.size)] = 1.0
            A[:, columns] = self._equations(None, unit, None, harmonics)
        return A

    def _w_columns(self, h: int, columns: np.ndarray) -> np.ndarray:
        """The reduced matrix's columns of the forces ``w`` on harmonic ``h``'s nonlinear rows
        (``columns``: their positions in ``R``): what :meth:`_equations` gives for unit ``w``, formed from
        the stuck receptance ``G̃_φ`` (:meth:`stuck_receptance`) and ``T_{S,φ} W_φ Ψ̃_φᴴ`` instead of the
        modal sums column by column."""
        m, bs = self.model, self.basis
        slot, coord = np.divmod(self.R[columns], m.p)
        cset, pos = np.unique(coord, return_inverse=True)
        pick = pos + np.where(slot == 2 * h, cset.size, 0) if h else pos     # sine slots: the b columns

        def real_columns(block):                  # complex (r × |cset|) → its real form's picked columns
            return block.real[:, pick] if h == 0 else real_block(block)[:, pick]

        phi = self.phi[h]
        explicit = (bs.T_S[h][:, phi] / self.zt[h][phi]) @ bs.PsiH[h][phi][:, cset]
        dy = np.zeros((m.n_core, columns.size))
        dy[m._rows(h)] = real_columns(-self.stuck_receptance(h)[:, cset])
        dy[m.eta_slices[h]] = real_columns(-explicit)
        unit = np.zeros((self.R.size, columns.size))
        unit[columns, np.arange(columns.size)] = 1.0
        parts = [unit - self._apply_dK(dy[:m.n_d])]
        for k in range(m.H + 1):
            block = real_columns(bs.PsiH[h][self.rho[h]][:, cset]) if k == h else None
            parts.append(np.zeros((self._e_size(k), columns.size)) if block is None else block)
        if self.ng:
            gauge = self.core.rotation.gauge.T @ dy[m.eta_slices[0]][m.zero_modes] if h == 0 else None
            parts.append(np.zeros((self.ng, columns.size)) if gauge is None else gauge)
        parts.append(self.rows[:, :m.n_core] @ dy)
        return np.vstack(parts)

    def stuck_receptance(self, h: int) -> np.ndarray:
        """``G̃_φ = Ψ̃_φ diag(1/(ω̃² − s)) Ψ̃_φᴴ`` of harmonic ``h`` over the stuck modes eliminated (p × p):
        the basis's series where the resonant modes are among those it sums directly, else the direct sum."""
        phi, rho = self.phi[h], self.rho[h]
        receptance = self.basis.receptances[h]
        if h == 0:
            return receptance
        if receptance is not None and np.all(np.isin(rho, receptance.near)):
            return receptance((h * self.core.omega) ** 2 + 1j * h * self.core.omega * self.core.xi, exclude=rho)
        Psi = self.basis.Psi[h][:, phi]
        return (Psi / self.zt[h][phi]) @ Psi.conj().T

    # ---- solves --------------------------------------------------------------------------------
    def solve(self, b: np.ndarray) -> np.ndarray:
        """``J⁻¹ b``: :meth:`reduced_solve`, refined once on the residual ``b − J x`` (``J`` applied as the
        operator: the stuck modes carry rounding of ``ε max ω̃²`` from their eigendecomposition, which the
        step removes)."""
        x = self.reduced_solve(b)
        return x + self.reduced_solve(b - apply(self.J, x))

    def reduced_solve(self, b: np.ndarray) -> np.ndarray:
        """``J⁻¹ b`` through the reduced system, then the core unknowns lifted from its solution."""
        m = self.model
        b = np.asarray(b, float)
        core, ext = b[:m.n_core, None], b[m.n_core:, None]
        rhs = -self._equations(core, np.zeros((self.order, 1)), ext, range(m.H + 1))
        u = sla.lu_solve(self.lu, rhs * self.row_scale[:, None], check_finite=False) * self.col_scale[:, None]
        w, e, mu, t = self._split(u)
        dy = self._lift(core - self.columns @ t, w, e, mu, range(m.H + 1))[0]
        return np.concatenate([dy[:, 0], t[:, 0]])
