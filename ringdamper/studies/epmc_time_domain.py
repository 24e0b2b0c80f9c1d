"""Is a rising EPMC frequency the EPMC's answer or a harmonic-balance artefact?
(docs/investigations/epmc_time_domain.md).

For a structure with Jenkins contacts, the backbone of the first stuck mode is traced by the HBM
at several harmonic truncations H (:func:`ringdamper.nonlinear.harmonic_balance.epmc.epmc`) and, at every
``shoot_every``-th amplitude, the periodic orbit of the EPMC equation is found again in the time
domain by shooting from the highest-H solution (:mod:`ringdamper.nonlinear.time_domain.shooting`) at two step
counts (Δt convergence). The table also holds the one-period return error of the HBM state with
its own ω and ξ and with the stuck ω or ξ = 0 (a measure that tells a periodic orbit from a
near miss), and the mode content that explains a rise: the share of the fundamental's mass norm
``|φ_kᵀ M Q_1|²/α²`` in each mode ``φ_k`` of the structure *without* the contact springs (the
free system) and the fraction of the period each element slips.

The study's six analyses on the Jenkins chain family (:mod:`ringdamper.studies.jenkins_chains`),
one table each: :func:`rise_scan`, :func:`worst_comparisons`, :func:`spurious_returns`,
:func:`viscous_analogue`, :func:`step_study` and :func:`issue_chain_check`.
"""
from __future__ import annotations

import logging
import time

import numpy as np
import pandas as pd
import scipy.linalg as sla

from ringdamper.nonlinear.contact.friction import FrictionContacts, contact_aft
from ringdamper.nonlinear.fourier import Fourier
from ringdamper.nonlinear.harmonic_balance.epmc import Backbone, epmc, linear_limit
from ringdamper.nonlinear.harmonic_balance.structure import Structure
from ringdamper.nonlinear.time_domain.shooting import hbm_state, phase_row, return_error, shoot
from ringdamper.status import Status
from ringdamper.studies.jenkins_chains import ISSUE_GRID, OPTIONS, SEEDS, chain_grid, issue_chain, jenkins_chain

LOG = logging.getLogger(__name__)

SIMPLEST = 149                            # the simplest rising chain: two masses, one element
SPURIOUS = 179                            # its H = 3 backbone holds a branch no other H finds
STEP_POINTS = ((43, 15), (SIMPLEST, 6))   # (seed, dense-grid point): top of the grid, first strong slip
VISCOUS_DAMPERS = np.r_[0.0, np.geomspace(0.1, 1e3, 9)]   # c of the viscous analogue


def stuck_frequency(structure: Structure, contacts: FrictionContacts) -> float:
    """ω of the first linearised stuck mode (the start of the backbone) [rad/s]."""
    return float(structure.stuck_modes(contacts.stuck_stiffness().ravel())[0][0])


def first_slip(structure: Structure, contacts: FrictionContacts) -> float:
    """Modal amplitude at which the first stuck mode makes a pair slip (``linear_limit``)."""
    phi = structure.stuck_modes(contacts.stuck_stiffness().ravel())[1][:, 0]
    return float(linear_limit(structure, contacts, phi))


def frequency_rise(backbone: Backbone, omega_stuck: float) -> float:
    """Largest ``ω/ω_stuck − 1`` over the converged points of a backbone (NaN if none)."""
    ok = backbone.status == Status.CONVERGED
    return float(np.max(backbone.omega[ok]) / omega_stuck - 1) if np.any(ok) else float("nan")


def mode_content(backbone: Backbone, contacts: FrictionContacts, i: int, nt: int = 1024):
    """Free-system frequencies ``ω_free`` (modes of ``(K, M)`` without contact springs), the share
    of point ``i``'s fundamental in each of those modes, and the fraction of the period each
    element's tangential force sits on its slip limit ``μN`` (direction t1)."""
    st = backbone.model.structure
    hd = st.harmonics[1]
    w2, Phi = sla.eigh(np.real(hd.K), np.real(hd.M))
    Q1 = st.modal(1).Phi @ backbone.eta[1][i]
    share = np.abs(Phi.T @ np.real(hd.M) @ Q1) ** 2 / backbone.alpha[i] ** 2
    d = backbone.d[i].reshape(backbone.model.C, contacts.npairs, 3).transpose(1, 2, 0)
    aft = contact_aft(contacts, Fourier(backbone.H, nt), d, jacobian=False)
    limit = contacts.mu[:, None] * aft.normal
    slipping = np.abs(np.abs(aft.tangential[:, 0]) - limit) <= 1e-9 * np.maximum(limit, 1e-300)
    return np.sqrt(np.maximum(w2, 0.0)), share, np.mean(slipping, axis=1)


def damper_poles(structure: Structure, element: int, dampers: np.ndarray) -> pd.DataFrame:
    """Linear viscous analogue of a slipping element: poles ``s`` of ``M s² + c b bᵀ s + K = 0``
    (no contact springs; ``b`` the element's t1 row of ``B``) for every ``c`` of ``dampers``, one
    row per ``c`` and pole with ``Im s > 0`` (``Im s = 0``: overdamped), ascending in ``Im s``."""
    hd = structure.harmonics[0]
    M, K = np.real(hd.M), np.real(hd.K)
    b = np.real(hd.B[3 * element + 1])
    n = M.shape[0]
    rows = []
    for c in dampers:
        A = np.block([[np.zeros((n, n)), np.eye(n)],
                      [-np.linalg.solve(M, K), -np.linalg.solve(M, c * np.outer(b, b))]])
        s = np.linalg.eigvals(A)
        s = np.sort_complex(s[s.imag >= 0] * -1j) * 1j                    # by Im s
        rows += [dict(c=c, pole=k, real=z.real, imag=z.imag) for k, z in enumerate(s)]
    return pd.DataFrame(rows)


def compare(structure_at, contacts: FrictionContacts, alpha: np.ndarray, harmonics=(1, 3, 7, 15),
            shoot_every: int = 3, n_steps=(2048, 4096), nt: int = 1024) -> pd.DataFrame:
    """One row per amplitude of ``alpha`` and per H: ω, ζ and status of the HBM; on every
    ``shoot_every``-th amplitude from the first (rows of the highest H) the shooting's ω, ζ at the
    step counts ``n_steps``, its Newton iterations and CPU time, the return errors of the HBM
    state and the mode content. ``structure_at(H)`` builds the structure with H harmonics."""
    rows, top = [], None
    for H in harmonics:
        t0 = time.process_time()
        bb = epmc(structure_at(H), contacts, alpha, H=H, nt=max(nt, 2 * H + 1), tol=1e-10)
        LOG.info("H = %d: %.1f s CPU, statuses %s", H, time.process_time() - t0, bb.status)
        rows += [dict(H=H, alpha=alpha[i], omega=bb.omega[i], zeta=bb.zeta[i],
                      status=int(bb.status[i])) for i in range(alpha.size)]
        top = bb
    st = top.model.structure
    w_stuck = stuck_frequency(st, contacts)
    g = phase_row(top)
    table = pd.DataFrame(rows)
    table["omega_stuck"] = w_stuck
    table["alpha_slip"] = first_slip(st, contacts)
    extra = []
    for i in range(0, alpha.size, shoot_every):
        if top.status[i] != Status.CONVERGED:
            continue
        x0, omega, xi = hbm_state(top, contacts, i)
        row = dict(H=top.H, alpha=alpha[i])
        w_free, share, slip = mode_content(top, contacts, i)
        k = int(np.argmax(share))
        row.update(free_mode=k, omega_free=w_free[k], free_share=share[k],
                   slip_fraction=";".join(f"{s:.2f}" for s in slip),
                   return_hbm=return_error(st, contacts, x0, omega, xi, n_steps[0]),
                   return_stuck_omega=return_error(st, contacts, x0, w_stuck, xi, n_steps[0]),
                   return_xi0=return_error(st, contacts, x0, omega, 0.0, n_steps[0]))
        for n in n_steps:
            t0 = time.process_time()
            try:
                res = shoot(st, contacts, alpha[i], x0, omega, xi, g, n_steps=n)
                row.update({f"omega_shoot_{n}": res.omega, f"zeta_shoot_{n}": res.zeta,
                            f"newton_{n}": res.iterations,
                            f"cpu_shoot_{n}": time.process_time() - t0})
            except RuntimeError as err:
                LOG.warning("alpha = %.4g, %d steps: %s", alpha[i], n, err)
        extra.append(row)
    return table.merge(pd.DataFrame(extra), on=["H", "alpha"], how="left")


def step_convergence(structure: Structure, contacts: FrictionContacts, backbone: Backbone, i: int,
                     n_steps=(256, 512, 1024, 2048, 4096, 8192, 16384)) -> pd.DataFrame:
    """Shooting's ω, ζ at point ``i`` of ``backbone`` for every step count of ``n_steps`` and
    their differences to the finest (the integrator's Δt convergence)."""
    x0, omega, xi = hbm_state(backbone, contacts, i)
    g = phase_row(backbone)
    rows = []
    for n in n_steps:
        res = shoot(structure, contacts, backbone.alpha[i], x0, omega, xi, g, n_steps=n)
        rows.append(dict(alpha=backbone.alpha[i], n_steps=n, omega=res.omega, zeta=res.zeta,
                         newton=res.iterations))
    t = pd.DataFrame(rows)
    return t.assign(d_omega_rel=(t.omega / t.omega.iloc[-1] - 1).abs(),
                    d_zeta=(t.zeta - t.zeta.iloc[-1]).abs())


def return_check(structure_at, contacts: FrictionContacts, alpha: np.ndarray, H: int,
                 nt: int = 1024, n_steps: int = 2048) -> pd.DataFrame:
    """Return error of every converged point of the H-harmonic backbone (a periodicity check of
    that truncation's solutions, e.g. a branch that only one H finds)."""
    bb = epmc(structure_at(H), contacts, alpha, H=H, nt=nt, tol=1e-10)
    st = bb.model.structure
    rows = []
    for i in np.flatnonzero(bb.status == Status.CONVERGED):
        x0, omega, xi = hbm_state(bb, contacts, i)
        rows.append(dict(H=H, alpha=alpha[i], omega=omega, zeta=bb.zeta[i],
                         return_hbm=return_error(st, contacts, x0, omega, xi, n_steps)))
    return pd.DataFrame(rows)


def dense_grid(structure: Structure, contacts: FrictionContacts) -> np.ndarray:
    """The family grid with 16 points: every third one is a point of the 6-point family grid."""
    return chain_grid(structure, contacts, n=16)


def rise_scan() -> pd.DataFrame:
    """Every chain of the family (``SEEDS``): its masses, elements, ω_stuck and the frequency rise
    ``max ω/ω_stuck − 1`` of its backbone at H = 1 on the family's grid and settings (``OPTIONS``)."""
    t0 = time.process_time()
    rises = []
    for seed in SEEDS:
        st, c = jenkins_chain(seed)
        bb = epmc(st, c, chain_grid(st, c), **OPTIONS)
        rises.append(dict(seed=seed, masses=st.harmonics[0].M.shape[0], elements=c.npairs,
                          omega_stuck=stuck_frequency(st, c),
                          rise=frequency_rise(bb, stuck_frequency(st, c))))
    rise = pd.DataFrame(rises)
    LOG.info("scan: %.1f s CPU, %d of %d chains rise", time.process_time() - t0,
             int((rise.rise > 1e-6).sum()), len(rise))
    return rise


def worst_comparisons(rise: pd.DataFrame) -> dict[int, pd.DataFrame]:
    """seed -> :func:`compare` table on the :func:`dense_grid` (H = 1, 3, 7, 15, shooting at every third
    amplitude) of the two chains with the largest rise of the :func:`rise_scan` table ``rise`` and of
    ``SIMPLEST``."""
    worst = list(rise.sort_values("rise", ascending=False).seed.iloc[:2])
    tables = {}
    for seed in worst + [SIMPLEST]:
        t0 = time.process_time()
        st, c = jenkins_chain(seed)
        tables[seed] = compare(lambda H, s=seed: jenkins_chain(s, H=H)[0], c, dense_grid(st, c))
        LOG.info("seed %d: %.1f s CPU", seed, time.process_time() - t0)
    return tables


def spurious_returns() -> pd.DataFrame:
    """The :func:`return_check` of ``SPURIOUS``'s backbones at H = 3 and H = 15 on the family grid."""
    st, c = jenkins_chain(SPURIOUS)
    return pd.concat([return_check(lambda H: jenkins_chain(SPURIOUS, H=H)[0], c, chain_grid(st, c), H)
                      for H in (3, 15)])


def viscous_analogue() -> pd.DataFrame:
    """The :func:`damper_poles` of ``SIMPLEST`` with its element replaced by each damper of
    ``VISCOUS_DAMPERS``."""
    return damper_poles(jenkins_chain(SIMPLEST)[0], 0, VISCOUS_DAMPERS)


def step_study() -> pd.DataFrame:
    """The :func:`step_convergence` at each (seed, point) of ``STEP_POINTS`` on the seed's H = 15
    backbone of the :func:`dense_grid`."""
    steps = []
    for seed, i in STEP_POINTS:
        st, c = jenkins_chain(seed, H=15)
        bb = epmc(st, c, dense_grid(st, c), H=15, nt=1024, tol=1e-10)
        steps.append(step_convergence(st, c, bb, i).assign(seed=seed))
    return pd.concat(steps)


def issue_chain_check() -> pd.DataFrame:
    """The folding chain (:func:`~ringdamper.studies.jenkins_chains.issue_chain`, ζ up to 0.41) on
    ``ISSUE_GRID``: :func:`compare` at H = 1 and 15 with shooting at every amplitude, and the return
    error of its H = 1 backbone (column ``return_h1``)."""
    st, c = issue_chain()
    hd = st.harmonics[1]

    def issue_at(H):
        return Structure.real(hd.M, hd.K, hd.B, hd.response, hd.force, H=H)

    table = compare(issue_at, c, ISSUE_GRID, harmonics=(1, 15), shoot_every=1)
    returns = return_check(issue_at, c, ISSUE_GRID, 1).rename(columns={"return_hbm": "return_h1"})
    return table.merge(returns[["H", "alpha", "return_h1"]], on=["H", "alpha"], how="left")
