"""dNNM + E-EBM stage of one geometry (paper §2.5.3; docs/design.md §3.4, §4): reduced.nc + static.nc -> dnnm.nc.

The reduced model is read in its own modal coordinates: per harmonic h, mass-normalised modes with
eigenvalues w_r^2, their relative contact coordinates B phi_r and their response (blade-tip Z) value
phi_r,tip. In these coordinates M_h = I, K_h = diag(w_r^2), B_h = [B phi_r], the response row is
[phi_r,tip] and the harmonic-1 forcing (unit Z force at the tip) is its conjugate: an exact
representation of the reduced model, so the condensation of
``nonlinear.harmonic_balance.condensed`` sums over all of it.
"""

from __future__ import annotations

import logging
import time

import numpy as np
import xarray as xr

from ringdamper.io import declared_dataset, nan_values, variable
from ringdamper.nonlinear.adaptive import RAISE_BUDGET_LUS, TRUNCATION_FLAGS, adapt_harmonics
from ringdamper.nonlinear.contact.friction import FrictionContacts
from ringdamper.nonlinear.harmonic_balance.eebm import eebm
from ringdamper.nonlinear.harmonic_balance.epmc import epmc
from ringdamper.nonlinear.harmonic_balance.structure import HarmonicData, Structure
from ringdamper.nonlinear.indicators.conditioning import ILL_CONDITIONED
from ringdamper.nonlinear.indicators.separation import warn_separation
from ringdamper.nonlinear.indicators.truncation import warn_truncation
from ringdamper.nonlinear.normalisation import normalised_frequency
from ringdamper.status import CHAIN_FAILED, Status

log = logging.getLogger(__name__)

#: arc-length points a ring's continuation, and that of a point solved again at a higher H
#: (docs/nonlinear_core.md §4.5), may spend past a fold in α (the driver's default is 400).
#: Measured on the 81 rings of an adaptive campaign (docs/nonlinear_core.md §4.1): 13 went past a fold,
#: they used 1-84 points, and the latest grid value any of them solved came 65 points into the arc; the
#: one ring that used 400 (210 s, 21 times the median) solved its last grid value at the 4th and spent
#: the 395 others in the lift-off stretch without reaching the next.
ARC_POINTS = 100


def structure_from_reduced(reduced: xr.Dataset, n_harmonics: int, field: str = "dnnm.n_harmonics") -> Structure:
    """Per-harmonic modal data of ``reduced.nc`` as a cyclic :class:`Structure` (h = 0..H); ``field``
    names the setting that asked for H in the error when reduced.nc holds fewer harmonics.

    The shapes are taken C-ordered whatever the dataset's memory layout (the reduction's own
    dataset holds strided views, one read from reduced.nc contiguous arrays): BLAS rounds a product
    by the layout of its operands, and the held points at the top of the amplitude grid
    (docs/nonlinear_core.md §4.3) amplify that rounding into another path, so the stage must
    compute the same arithmetic from either."""
    H = int(n_harmonics)
    available = int(reduced.sizes["harmonic"]) - 1
    if H > available:
        raise ValueError(f"{field} = {H} exceeds the {available} harmonics of reduced.nc "
                         f"(reduction.n_harmonics): allowed [1, {available}]")
    data = []
    for h in range(H + 1):
        r = reduced.isel(harmonic=h)
        w2 = r.omega2.values
        contact = _c_ordered(r.contact_shape_real) + 1j * _c_ordered(r.contact_shape_imag)  # (mode, pair, dir)
        psi = contact.reshape(len(w2), -1).T                                       # (3 pairs, mode)
        res = _c_ordered(r.response_shape_real) + 1j * _c_ordered(r.response_shape_imag)
        if h == 0:
            psi, res = psi.real, res.real
        force = np.conj(res) if h == 1 else np.zeros_like(res)
        data.append(HarmonicData(M=np.eye(len(w2)), K=np.diag(w2), B=psi, response=res, force=force))
    return Structure(data, n_sectors=int(reduced.attrs["n_sectors"]),
                     engine_order=int(reduced.attrs["engine_order"]))


def _c_ordered(variable: xr.DataArray) -> np.ndarray:
    return np.ascontiguousarray(variable.values)


def contacts_from_static(static: xr.Dataset, contact_cfg: dict, law: str = "jenkins") -> FrictionContacts:
    """Friction elements from the static state: preload N0 on closed pairs, gap on open ones."""
    n0 = static.N0.values
    return FrictionContacts(kn=static.kn.values, kt=static.kt.values,
                            mu=contact_cfg["friction_coefficient"],
                            N0=np.where(n0 > 0, n0, 0.0), gap=np.where(n0 > 0, 0.0, static.gap.values),
                            law=law)


def target_stuck_frequency(structure: Structure, contacts: FrictionContacts, target_hz: float) -> float:
    """Linearised stuck frequency (rad/s) of the harmonic-1 mode nearest ``target_hz``."""
    omegas, _ = structure.stuck_modes(contacts.stuck_stiffness().ravel(), h=1)
    return float(omegas[np.argmin(np.abs(omegas - 2 * np.pi * target_hz))])


def amplitude_grid(dnnm_cfg: dict) -> np.ndarray:
    """The common modal-amplitude grid alpha (kg^1/2 m), log-spaced (docs/design.md §4)."""
    return np.geomspace(dnnm_cfg["amplitude_min"], dnnm_cfg["amplitude_max"], dnnm_cfg["n_amplitudes"])


def solve_backbone(reduced: xr.Dataset, static: xr.Dataset, config: dict, target_hz: float,
                   alpha: np.ndarray, n_harmonics: int, nt: int | None = None,
                   structure_harmonics: int | None = None):
    """EPMC backbone of the mode nearest ``target_hz`` at ``n_harmonics`` (``nt`` AFT samples, default
    :func:`ringdamper.nonlinear.fourier.default_nt`) on ``alpha``, and its E-EBM:
    ``(backbone, contacts, eebm result, omega_stuck)``. The backbone's structure holds harmonics up
    to ``structure_harmonics`` (default ``n_harmonics``; more lets its points be solved again at
    a higher truncation)."""
    cfg = config["dnnm"]
    structure = structure_from_reduced(reduced, n_harmonics)
    if structure_harmonics is not None and structure_harmonics > n_harmonics:
        structure = structure_from_reduced(reduced, structure_harmonics, "dnnm.max_harmonics")
    contacts = contacts_from_static(static, config["contact"], cfg["friction_law"])
    omega_stuck = target_stuck_frequency(structure, contacts, target_hz)
    backbone = epmc(structure, contacts, alpha, H=n_harmonics, nt=nt, omega_target=omega_stuck,
                    tol=cfg.get("continuation_tolerance", 1e-8), max_arc_points=ARC_POINTS)
    return backbone, contacts, eebm(backbone, zeta_s=cfg["structural_damping_ratio"]), omega_stuck


def run_dnnm(reduced: xr.Dataset, static: xr.Dataset, config: dict, target_hz: float,
             omega_stuck_default: float) -> xr.Dataset:
    """Backbone (EPMC) of the mode nearest ``target_hz`` at ``dnnm.n_harmonics``, its points solved
    again at up to ``dnnm.max_harmonics`` where their indicators ask for it
    (:mod:`ringdamper.nonlinear.adaptive`), and their E-EBM, as the dnnm.nc dataset."""
    cfg = config["dnnm"]
    start = time.perf_counter()
    alpha = amplitude_grid(cfg)
    H0, H_max = cfg["n_harmonics"], max_harmonics(cfg)
    backbone, contacts, _, omega_stuck = solve_backbone(reduced, static, config, target_hz, alpha, H0,
                                                        cfg["n_time_samples"], structure_harmonics=H_max)
    adaptive = adapt_harmonics(backbone, contacts, H_max, cfg["structural_damping_ratio"],
                               tol=cfg.get("continuation_tolerance", 1e-8), max_arc_points=ARC_POINTS,
                               raise_budget_lus=raise_budget(cfg))
    out = adaptive.values
    warn_truncation(out["highest_harmonic_energy"], alpha)
    warn_separation(out["lifting_pairs"], alpha, int(adaptive.n_harmonics.max()))
    values = {"omega0": normalised_frequency(out["omega"], omega_stuck_default), "frequency": out["frequency"],
              "zeta": out["zeta"], "gamma": out["gamma"], "phi": out["phi"], "q_res_z": out["q_res_peak"],
              "q_res_z_h1": out["q_res_h1"], "energy_dissipated": out["energy_dissipated"],
              "energy_damping": out["e_damp"], "rigid_body_imbalance": out["drift"],
              "highest_harmonic_energy": out["highest_harmonic_energy"],
              "normal_force_ratio_min": out["normal_force_ratio_min"], "lifting_pairs": out["lifting_pairs"],
              "n_harmonics": adaptive.n_harmonics.astype(float), "jacobian_condition": out["jacobian_condition"],
              "ill_conditioned": (out["jacobian_condition"] > ILL_CONDITIONED).astype(np.int8),
              "truncation_flag": out["truncation_flag"], "truncation_error": out["truncation_error"]}
    attrs = {"kappa": np.asarray(static.attrs["kappa"], dtype=float), "n_harmonics": H0,
             "max_harmonics": H_max, "n_time_samples": cfg["n_time_samples"],
             "friction_law": cfg["friction_law"], "structural_damping_ratio": cfg["structural_damping_ratio"],
             "omega_stuck": omega_stuck, "omega_stuck_default": omega_stuck_default,
             "raise_budget_lus": raise_budget(cfg), "harmonics_resolved": adaptive.resolved,
             "harmonics_failed": "; ".join(adaptive.notes),
             "unsolved_reason": first_unsolved_reason(alpha, out["status"], adaptive.reason),
             "wall_time_s": time.perf_counter() - start}
    return dnnm_dataset(alpha, contacts.npairs, values, out["status"], attrs)


def first_unsolved_reason(alpha: np.ndarray, status, reason: list) -> str:
    """Why the continuation stopped: the first grid point with status NO_CONVERGENCE, its amplitude and
    the driver's reason ("" if every point was reached)."""
    unsolved = np.flatnonzero(np.asarray(status) == Status.NO_CONVERGENCE)
    if not unsolved.size:
        return ""
    i = int(unsolved[0])
    return f"alpha = {alpha[i]:.4g}: {reason[i]}"


def max_harmonics(dnnm_cfg: dict) -> int:
    """The largest truncation of the adaptive harmonics, ``dnnm.max_harmonics`` (default: the base
    ``dnnm.n_harmonics``, no adaptation)."""
    return int(dnnm_cfg.get("max_harmonics", dnnm_cfg["n_harmonics"]))


def raise_budget(dnnm_cfg: dict) -> int:
    """LU factorisations a point's raise by 2 harmonics may make, ``dnnm.raise_budget_lus`` (default
    :data:`ringdamper.nonlinear.adaptive.RAISE_BUDGET_LUS`)."""
    return int(dnnm_cfg.get("raise_budget_lus", RAISE_BUDGET_LUS))


#: The variables of dnnm.nc besides ``status``: name -> (dims, units, long_name). The one declaration
#: of the file, shared by a solved geometry and a failed one.
DNNM_VARIABLES = {
    "omega0": ("amplitude", "1", "normalised resonant frequency 2.195 omega / omega_stuck,default"),
    "frequency": ("amplitude", "Hz", "resonant frequency"),
    "zeta": ("amplitude", "1", "modal damping ratio of the dNNM"),
    "gamma": ("amplitude", "N", "forcing level (E-EBM)"),
    "phi": ("amplitude", "rad", "forcing phase (E-EBM)"),
    "q_res_z": ("amplitude", "m", "peak of the blade-tip Z displacement over the period"),
    "q_res_z_h1": ("amplitude", "m", "first-harmonic magnitude of the blade-tip Z displacement"),
    "energy_dissipated": (("amplitude", "pair"), "J", "energy dissipated per cycle by each contact pair"),
    "energy_damping": ("amplitude", "J",
                       "energy per cycle of the structural and dNNM damping (E-EBM E_damp)"),
    "rigid_body_imbalance": (
        "amplitude", "1",
        "mean force on the ring's free rigid-body modes (rotation about Z, axial) held by the gauge, "
        "relative to the contact forces: the ratcheting drive"),
    "highest_harmonic_energy": (
        "amplitude", "1",
        "fraction of the vibration energy in the highest harmonic H (truncation indicator; NaN at H = 1)"),
    "normal_force_ratio_min": (
        "amplitude", "1",
        "smallest unclipped normal force over the period relative to its preload, over the preloaded pairs "
        "(separation indicator: <= 0 where a pair lifts off)"),
    "lifting_pairs": ("amplitude", "1", "number of preloaded pairs that lift off during part of the period"),
    "n_harmonics": ("amplitude", "1",
                    "harmonics H of the point's solution (dnnm.n_harmonics, raised point by point up to "
                    "dnnm.max_harmonics where its truncation or separation indicator asks for it)"),
    "jacobian_condition": (
        "amplitude", "1",
        "1-norm condition number (LAPACK estimate) of the converged point's Newton Jacobian, unknowns scaled "
        "as Newton's convergence test and rows by their largest entry (NaN where not converged)"),
    "ill_conditioned": (
        "amplitude", "1",
        f"1 where jacobian_condition > {ILL_CONDITIONED:.3g} = 1e-6 / (2 eps): rounding (the BLAS kernel) may move "
        "the point by more than 1e-6 relative"),
    "truncation_flag": ("amplitude", "1",
                        "truncation of the point: " + ", ".join(f"{k} {v}" for k, v in TRUNCATION_FLAGS.items())
                        + " (dnnm.raise_budget_lus; the point keeps its last converged H)"),
    "truncation_error": ("amplitude", "1",
                         "estimated largest relative change of omega, zeta, gamma and q_res_z from raising a "
                         "flagged point's kept H by 2 (NaN where truncation_flag is 0)"),
}
STATUS_MEANING = ("0 converged, 1 no convergence, 2 not reached, 3 converged with the ring's mean "
                  "rigid-body equilibrium unbalanced (ratcheting), 4 budget, 99 the geometry's chain failed "
                  "(attribute reason)")


def dnnm_dataset(alpha, n_pairs: int, values: dict, status, attrs: dict) -> xr.Dataset:
    """dnnm.nc from its arrays: ``values`` holds exactly the variables of :data:`DNNM_VARIABLES`."""
    coords = {"amplitude": variable("amplitude", alpha, "kg0.5 m",
                                    "modal amplitude alpha (mass-normalised fundamental)"),
              "pair": variable("pair", np.arange(n_pairs), "1", "contact pair index")}
    ds = declared_dataset("dnnm.nc", DNNM_VARIABLES, values, coords, attrs)
    ds["status"] = variable("amplitude", np.asarray(status).astype(np.int8), "1", STATUS_MEANING)
    return ds


def failed_dnnm(config: dict, kappa, reason: str, n_pairs: int, status: int = CHAIN_FAILED) -> xr.Dataset:
    """dnnm.nc of a geometry whose chain failed: the variables of a solved one, all NaN, every point
    carrying ``status`` and the attribute ``reason``."""
    alpha = amplitude_grid(config["dnnm"])
    values = nan_values(DNNM_VARIABLES, {"amplitude": len(alpha), "pair": int(n_pairs)})
    return dnnm_dataset(alpha, n_pairs, values, np.full(len(alpha), status),
                        {"kappa": np.asarray(kappa, dtype=float), "reason": reason})


def default_normalisation(reduced: xr.Dataset, static: xr.Dataset, config: dict,
                          target_hz: float) -> dict:
    """What every geometry's dNNM is normalised by, computed once on the default ring: the target
    frequency of the modal stage and the default ring's linearised stuck frequency of the harmonic-1
    mode nearest it, ``omega_stuck_default_rad_s`` (the reference of ``normalised_frequency``)."""
    structure = structure_from_reduced(reduced, 1)
    contacts = contacts_from_static(static, config["contact"], config["dnnm"]["friction_law"])
    omega = target_stuck_frequency(structure, contacts, target_hz)
    log.info("omega_stuck_default = %.6f rad/s", omega)
    return {"target_frequency_hz": float(target_hz), "omega_stuck_default_rad_s": omega}


def dnnm_stage(reduced: xr.Dataset, static: xr.Dataset, config: dict, kappa,
               normalisation: dict) -> xr.Dataset:
    """The dNNM stage of geometry ``kappa`` (``normalisation`` from :func:`default_normalisation`).
    It never raises: a failed static state or solve gives :func:`failed_dnnm` (status 99 and the
    reason), so the campaign goes on."""
    try:
        if static.attrs["status"] != 0:
            raise RuntimeError(f"static solve failed: {static.attrs['reason']}")
        ds = run_dnnm(reduced, static, config, normalisation["target_frequency_hz"],
                      normalisation["omega_stuck_default_rad_s"])
    except Exception as err:  # a failed geometry must not stop the campaign
        log.exception("dNNM stage failed for kappa=%s", list(kappa))
        return failed_dnnm(config, kappa, f"{type(err).__name__}: {err}", reduced.sizes["pair"])
    counts = np.bincount(ds.status.values.astype(int), minlength=5)
    log.info("kappa=%s status counts %s wall %.1f s", list(kappa), counts.tolist(), ds.attrs["wall_time_s"])
    if ds.attrs["unsolved_reason"]:
        log.info("continuation stopped at %s", ds.attrs["unsolved_reason"])
    return ds
