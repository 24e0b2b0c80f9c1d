"""Benchmark of the isotropic Coulomb law's AFT (``law="coulomb"``) on the default ring's states.

The default ring through mesh -> static -> reduced (untimed), its dNNM backbone with the campaign's
law and fidelity (untimed), then at every converged grid point the contact AFT with the Coulomb law
and its Jacobian, timed (CPU seconds of this process) with the periodic state as the library computes
it (:func:`ringdamper.nonlinear.contact.coulomb.coulomb_slider`) and as it was computed before, marched period
after period for every pair (:func:`ringdamper.nonlinear.contact.coulomb.march`, up to 500 periods; a state
it does not settle counts as failed). Also the largest differences between the two where both settle.
:func:`run` returns the figures; it asserts nothing.
"""
from __future__ import annotations

import time

import numpy as np


def _slider_inputs(contacts, fourier, d):
    """Tangential displacements, slip radii and contact states of the slot array ``d`` (as the AFT)."""
    dt = fourier.synth(d)
    N = contacts.N0[:, None] + contacts.kn[:, None] * (dt[:, 0] - contacts.gap[:, None])
    closed = N > 0
    return dt[:, 1:], contacts.mu[:, None] * np.where(closed, N, 0.0) / contacts.kt[:, None], closed


def run(config: dict) -> dict:
    """Per grid point of the default ring's backbone: CPU ms of both methods and their differences."""
    from ringdamper.bench.dnnm import ring_inputs
    from ringdamper.nonlinear.contact.coulomb import coulomb_slider, march
    from ringdamper.nonlinear.fourier import Fourier
    from ringdamper.nonlinear.stage import amplitude_grid, contacts_from_static, default_normalisation, solve_backbone
    from ringdamper.studies.hub_calibration import crossing_speed

    cfg = config["dnnm"]
    reduced, static = ring_inputs(config, (0.0, 0.0, 0.0))
    target = default_normalisation(reduced, static, config, crossing_speed(config)[1])["target_frequency_hz"]
    backbone = solve_backbone(reduced, static, config, target, amplitude_grid(cfg), cfg["n_harmonics"],
                              cfg["n_time_samples"])[0]
    contacts = contacts_from_static(static, config["contact"], "coulomb")
    fourier = Fourier(cfg["n_harmonics"], cfg["n_time_samples"])
    rate = contacts.mu * contacts.kn / contacts.kt
    memory = np.zeros((contacts.npairs, 2))
    rows = []
    for i in np.flatnonzero(np.isfinite(backbone.omega)):
        d = backbone.d[i].reshape(backbone.model.C, contacts.npairs, 3).transpose(1, 2, 0)
        t, r, closed = _slider_inputs(contacts, fourier, d)
        scale = np.max(np.abs(t)) + np.max(r) + np.finfo(float).tiny
        start = time.process_time()
        W, dW = coulomb_slider(rate, fourier.E, t, r, closed, True, memory)
        new = time.process_time() - start
        start = time.process_time()
        try:
            W0, dW0 = march(rate, fourier.E, t, r, closed, True, memory, scale, 1e-13, 500)
        except RuntimeError:
            W0 = None
        old = time.process_time() - start
        row = {"alpha": float(backbone.alpha[i]), "slider_ms": 1e3 * new, "march_ms": 1e3 * old,
               "march_failed": W0 is None}
        if W0 is not None:
            row["max_state_difference"] = float(np.max(np.abs(W - W0)) / scale)
            row["max_derivative_difference"] = float(np.max(np.abs(dW - dW0)) / max(1.0, np.max(np.abs(dW0))))
        rows.append(row)
    new, old = (sum(row[k] for row in rows) for k in ("slider_ms", "march_ms"))
    return {"points": rows, "slider_total_ms": new, "march_total_ms": old, "speedup": old / new}
