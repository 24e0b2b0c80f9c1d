"""Convergence of the reduced model with the numbers of fixed-interface and interface modes (docs/design.md §6).

Reference: the full FE cyclic sector model (``ringdamper.modal.analysis.cyclic_modes`` and a direct sparse
solve), contact free and stuck. Measured per (n_fi, n_if):

* ``target_error``: relative error of the target mode's stuck frequency (the 1D family at the target
  ND, identified on the full model by ``modal.analysis.FamilyClassifier``);
* ``receptance_error``: (``receptance_errors`` per frequency) max over the evaluation frequencies
  (fractions of the target's stuck frequency, the band the dNNM backbone sweeps) of the relative
  Frobenius error of the contact-free receptance at the contact coordinates, H(w) = B (K_h - w^2
  M_h)^{-1} B^T, the operator the nonlinear stage condenses the linear DoFs into;
* ``max_error``: max relative error of the first ``n_modes`` frequencies (free and stuck) over the
  checked NDs (modes below 1 Hz, the ring's ND-0 rigid motions, are compared in absolute terms).

The Craig–Bampton model is computed once with the largest n_fi and truncated (exactly the same as a
recomputation), so the study costs one factorisation.
"""

from __future__ import annotations

import time

import numpy as np
import scipy.linalg as sla

from ringdamper.fem.cyclic import cyclic_transform, interblade_phase, project
from ringdamper.fem.linalg import factorize
from ringdamper.fem.model import SectorModel, contact_stiffness, relative_displacement_operator
from ringdamper.modal.analysis import FamilyClassifier, cyclic_modes, labelled_modes
from ringdamper.reduction.craig_bampton import craig_bampton, truncate
from ringdamper.reduction.partition import partition
from ringdamper.reduction.reduced import eigenfrequencies, reduce_harmonics, stuck_matrices

RIGID_HZ = 1.0


def full_receptance(model: SectorModel, sigma: float, omegas) -> list[np.ndarray]:
    """Contact-free receptance (3m x 3m) of the full cyclic sector at the contact coordinates."""
    T, _ = cyclic_transform(model.n_dofs, model.left_nodes, model.right_nodes, model.fixed_dofs,
                            model.sector_angle, sigma)
    Kk, Mk = project(T, model.K), project(T, model.M)
    Gk = (relative_displacement_operator(model) @ T).toarray()
    out = []
    for w in omegas:
        lu = factorize((Kk - w**2 * Mk).astype(complex))
        out.append(Gk @ lu.solve(np.ascontiguousarray(Gk.conj().T).astype(complex)))
    return out


def reduced_receptance(K, M, B, omegas) -> list[np.ndarray]:
    return [B @ sla.solve(K - w**2 * M, B.conj().T.astype(np.result_type(K, B))) for w in omegas]


def _rel(a, b):
    """Relative frequency error; a reference rigid mode (< RIGID_HZ) only needs a rigid match."""
    a, b = np.asarray(a), np.asarray(b)
    rigid = np.abs(b) < RIGID_HZ
    err = np.abs(a - b) / np.where(rigid, 1.0, np.abs(b))
    return np.where(rigid, np.where(np.abs(a) < RIGID_HZ, 0.0, np.inf), err)


def convergence_study(model: SectorModel, engine_order: int, kn, kt, n_fi_values, n_if_values,
                      harmonics=(0, 1, 2, 3), target_harmonic: int = 1, target_family: str = "1D",
                      n_modes: int = 10, band=(0.99, 0.996, 1.0)) -> list[dict]:
    """Rows {n_fi, n_if, size, time_s, target_error, receptance_error, max_error} (see module doc)."""
    Kc = contact_stiffness(model, kn, kt)
    ref = {}
    for h in harmonics:
        sigma = interblade_phase(h, model.n_sectors, engine_order)
        ref[h] = {"sigma": sigma,
                  "free": cyclic_modes(model, model.K, model.M, 0, n_modes, sigma=sigma).frequency,
                  "stuck": cyclic_modes(model, model.K + Kc, model.M, 0, n_modes, sigma=sigma).frequency}
    sigma_t = interblade_phase(target_harmonic, model.n_sectors, engine_order)
    nd_t = int(round(abs(sigma_t) * model.n_sectors / (2 * np.pi)))
    freq, labels, _ = labelled_modes(model, model.K + Kc, nd_t, n_modes, FamilyClassifier(model))
    target = int(np.flatnonzero(np.asarray(labels) == target_family)[0])
    f_target = freq[target]
    omegas = 2 * np.pi * f_target * np.asarray(band)
    H_full = full_receptance(model, sigma_t, omegas)

    part = partition(model)
    t0 = time.perf_counter()
    cb_max = craig_bampton(model.K, model.M, part.boundary, part.interior, max(n_fi_values))
    t_cb = time.perf_counter() - t0
    rows = []
    for n_fi in n_fi_values:
        cb = truncate(cb_max, n_fi)
        for n_if in n_if_values:
            t0 = time.perf_counter()
            rs = reduce_harmonics(model, part, cb, engine_order, harmonics, n_if)
            t_h = time.perf_counter() - t0
            worst = 0.0
            for rh in rs.harmonics:
                f_free = eigenfrequencies(rh.K, rh.M, n_modes)
                f_stuck = eigenfrequencies(*stuck_matrices(rh, kn, kt), n_modes)
                worst = max(worst, _rel(f_free, ref[rh.harmonic]["free"]).max(),
                            _rel(f_stuck, ref[rh.harmonic]["stuck"]).max())
                if rh.harmonic == target_harmonic:
                    target_err = _rel(f_stuck[target], f_target)
                    H_red = reduced_receptance(rh.K, rh.M, rh.B, omegas)
                    rec_err = [float(np.linalg.norm(a - b) / np.linalg.norm(b))
                                   for a, b in zip(H_red, H_full)]
            rows.append({"n_fi": n_fi, "n_if": n_if, "size": rs.harmonics[0].size,
                         "time_s": t_h + t_cb * n_fi / max(n_fi_values),
                         "target_hz": float(f_target), "target_error": float(target_err),
                         "receptance_error": max(rec_err), "receptance_errors": rec_err, "max_error": float(worst)})
    return rows


def markdown_table(rows: list[dict]) -> str:
    band = len(rows[0]["receptance_errors"])
    head = ("| n_fi | n_if | DoFs | time (s) | target error | "
            + " | ".join(f"receptance error ({i + 1})" for i in range(band)) + " | max error ND 0–9 |")
    lines = [head, "|" + "---|" * (6 + band)]
    for r in rows:
        lines.append(f"| {r['n_fi']} | {r['n_if']} | {r['size']} | {r['time_s']:.1f} | "
                     f"{r['target_error']:.1e} | "
                     + " | ".join(f"{e:.1e}" for e in r["receptance_errors"])
                     + f" | {r['max_error']:.1e} |")
    return "\n".join(lines)


def study(config: dict) -> list[dict]:
    """The study on the default ring with the ``studies.reduction_convergence`` settings
    (``n_fixed_interface_modes``, ``n_interface_modes``: the values tried; ``band``: the receptance
    frequencies as fractions of the target's stuck frequency), contact stuck on every pair."""
    from ringdamper.fem.contact_law import stuck_pair_stiffness
    from ringdamper.fem.model import build_model
    from ringdamper.geometry.sector import build_sector

    s = config["studies"]["reduction_convergence"]
    model = build_model(build_sector(config, (0.0, 0.0, 0.0)), config)
    kn, kt = stuck_pair_stiffness(model.pairs.area, config["contact"])
    return convergence_study(model, config["operation"]["engine_order"], kn, kt,
                             s["n_fixed_interface_modes"], s["n_interface_modes"],
                             target_family=config["modal"]["target_family"], band=tuple(s["band"]))
