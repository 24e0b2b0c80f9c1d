"""One trial of the contact calibration: the default ring's backbone for one ``contact:`` section
and harmonic count H, and its row of the study (the contact parameters, the stuck frequency, the
static state's preload and the :mod:`.metrics` of the backbone).

The reduced model (contact-free, independent of the contact parameters) is read once per
:class:`DefaultRing`; the static contact state is re-solved for every trial (N0 depends on kn
through the penalty law), then the EPMC backbone + E-EBM of ``nonlinear.stage.run_dnnm`` on the
study's α grid, normalised by the stuck frequency of the trial's own contact parameters
(``nonlinear.stage.default_normalisation``).
"""

from __future__ import annotations

import copy
import time

import numpy as np

from ringdamper.nonlinear.normalisation import normalised_frequency

from .metrics import backbone_metrics, objective, shape_violations

# Physically plausible ranges (docs/calibration.md gives the reasons and references).
PLAUSIBLE = {
    "friction_coefficient": (0.2, 0.8),              # dry Ti–Ti / Ti-6Al-4V, run-in fretting contacts
    "normal_stiffness_per_area": (1.0e10, 1.0e12),   # N/m^3 at ~0.1–1 MPa nominal pressure
    "tangential_stiffness_per_area": (5.0e9, 1.0e12),
    "kt_over_kn": (0.5, 1.0),                        # Mindlin (elastic spheres): 2(1−ν)/(2−ν) = 0.80
}


def contact_section(mu: float, kn_area: float, kt_over_kn: float) -> dict:
    """The ``contact:`` section of a trial."""
    return {"friction_coefficient": float(mu), "normal_stiffness_per_area": float(kn_area),
            "tangential_stiffness_per_area": float(kt_over_kn * kn_area)}


def in_plausible_range(contact: dict) -> bool:
    """Whether a ``contact:`` section lies inside :data:`PLAUSIBLE`."""
    vals = dict(contact, kt_over_kn=contact["tangential_stiffness_per_area"]
                / contact["normal_stiffness_per_area"])
    return all(lo * (1 - 1e-12) <= vals[k] <= hi * (1 + 1e-12) for k, (lo, hi) in PLAUSIBLE.items())


class DefaultRing:
    """The default ring's inputs, loaded once: sector model, reduced model, target frequency."""

    def __init__(self, config: dict, reduced_path: str, target_hz: float):
        from ringdamper.fem.model import build_model
        from ringdamper.geometry.sector import build_sector
        from ringdamper.io import read_netcdf

        self.config = config
        self.model = build_model(build_sector(config, (0.0, 0.0, 0.0)), config)
        self.reduced = read_netcdf(reduced_path)
        self.target_hz = float(target_hz)

    def static(self, contact: dict):
        """Static contact state (static.nc dataset) for the trial's contact parameters."""
        from ringdamper.static.stage import solve_static, static_dataset

        cfg = dict(self.config, contact=contact)
        result, prob = solve_static(self.model, cfg)
        if result.status != 0:
            raise RuntimeError(f"static solve failed: {result.reason}")
        return static_dataset(self.model, result, prob, (0.0, 0.0, 0.0), cfg["operation"]["speed_rpm"])


def run_trial(ring: DefaultRing, contact: dict, H: int, alpha):
    """One backbone of the default ring on the α grid ``alpha`` = (first, last, count): returns
    (row dict, dnnm dataset)."""
    from ringdamper.nonlinear.stage import default_normalisation, run_dnnm

    t0 = time.perf_counter()
    cfg = copy.deepcopy(ring.config)
    cfg["contact"] = dict(contact)
    cfg["dnnm"].update(n_harmonics=int(H), max_harmonics=int(H), amplitude_min=alpha[0], amplitude_max=alpha[1],
                       n_amplitudes=int(alpha[2]))
    static = ring.static(cfg["contact"])
    w_stuck = default_normalisation(ring.reduced, static, cfg, ring.target_hz)["omega_stuck_default_rad_s"]
    ds = run_dnnm(ring.reduced, static, cfg, ring.target_hz, w_stuck)
    m = backbone_metrics(ds.q_res_z.values, 2 * np.pi * ds.frequency.values, ds.zeta.values,
                         ds.status.values, w_stuck)
    row = {"H": int(H), **{k: contact[k] for k in contact},
           "kt_over_kn": contact["tangential_stiffness_per_area"] / contact["normal_stiffness_per_area"],
           "stuck_hz": w_stuck / (2 * np.pi), "n_in_contact": int(static.attrs["n_in_contact"]),
           "mean_pressure_pa": float(np.sum(static.N0.values) / np.sum(static.area.values)),
           **m.row(), "objective": objective(m), "shape_violations": shape_violations(m),
           "wall_s": time.perf_counter() - t0}
    return row, ds


def trial_curve(ds) -> dict:
    """The backbone of a trial's dnnm dataset as arrays over α: ``alpha``, ``q`` (|q_res,z|, m),
    ``omega0`` (2.195 ω / ω_stuck, ω_stuck the linearised stuck frequency of the backbone, the
    dataset's ``omega_stuck``), ``zeta``, ``gamma`` (N) and ``status``."""
    return {"alpha": ds.amplitude.values, "q": ds.q_res_z.values,
            "omega0": normalised_frequency(2 * np.pi * ds.frequency.values, ds.attrs["omega_stuck"]),
            "zeta": ds.zeta.values, "gamma": ds.gamma.values, "status": ds.status.values}


def run_trials(config: dict, reduced_path, target_hz: float, alpha, trials) -> list[tuple[dict, dict]]:
    """``trials`` = [(contact section, H)] one after the other on one :class:`DefaultRing`:
    ``[(row, curve)]`` (:func:`run_trial`, :func:`trial_curve`). A trial that raises gives the row
    ``objective = inf`` with the error and the curve None: a failing trial is a result of the study."""
    ring = DefaultRing(config, reduced_path, target_hz)
    out = []
    for contact, H in trials:
        try:
            row, ds = run_trial(ring, contact, H, alpha)
            curve = trial_curve(ds)
        except Exception as err:  # a failing trial is a result of the study, not a crash of it
            row = {"H": H, **contact, "objective": float("inf"), "error": f"{type(err).__name__}: {err}"}
            curve = None
        out.append((row, curve))
    return out
