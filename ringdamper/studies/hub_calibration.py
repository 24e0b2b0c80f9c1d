"""Calibration of the dimensions Table 1 does not give (docs/design.md §2 "Blisk").

The hub (bore) axial thickness of the tapered web is chosen so that the first disk family (1D) at
the target nodal diameter crosses the engine-order line at the operating speed: Brent's method on
g(t_hub) = Omega_cross(t_hub) - Omega_op, each evaluation meshing the default ring, prestressing it
at three speeds and fitting Southwell's f^2 = a + b Omega^2 (``modal.analysis.eo_crossing``).
"""

from __future__ import annotations

import copy

import numpy as np
from scipy.optimize import brentq

from ringdamper.fem.model import build_model, stuck_contact_stiffness
from ringdamper.fem.prestress import rpm_to_rad_s
from ringdamper.geometry.sector import build_sector
from ringdamper.modal.analysis import campbell, eo_crossing, family_frequency

CALIBRATION_SPEED_FACTORS = (0.0, 0.9, 1.1)


def crossing_speed(config: dict, speed_factors=CALIBRATION_SPEED_FACTORS) -> tuple[float, float]:
    """(speed rpm, frequency Hz) of the target family x EO crossing for the default ring."""
    model = build_model(build_sector(config, (0.0, 0.0, 0.0)), config)
    omega_op = rpm_to_rad_s(config["operation"]["speed_rpm"])
    speeds = omega_op * np.asarray(speed_factors)
    modal = config["modal"]
    freq, labels = campbell(model, stuck_contact_stiffness(model, config["contact"]), speeds,
                            modal["target_nd"], modal["n_modes"])
    family = np.array([family_frequency(f, lab, modal["target_family"]) for f, lab in zip(freq, labels)])
    w, f = eo_crossing(speeds, family, config["operation"]["engine_order"])
    return w * 60 / (2 * np.pi), f


def calibrate_hub_thickness(config: dict, bracket, xtol: float) -> tuple[float, float]:
    """Hub thickness (m) putting the crossing at the operating speed, and the speed reached (rpm)."""
    target = config["operation"]["speed_rpm"]

    def miss(t_hub):
        trial = copy.deepcopy(config)
        trial["geometry"]["disk"]["hub_thickness"] = float(t_hub)
        return crossing_speed(trial)[0] - target

    t = brentq(miss, *bracket, xtol=xtol)
    return t, miss(t) + target


def study(config: dict) -> dict:
    """The calibration with the ``studies.hub_calibration`` settings (``bracket`` in m, ``xtol``),
    against the configured value and its crossing."""
    settings = config["studies"]["hub_calibration"]
    t_hub, rpm = calibrate_hub_thickness(config, settings["bracket"], settings["xtol"])
    rpm_configured, hz_configured = crossing_speed(config)
    return {"hub_thickness_m": float(t_hub), "crossing_speed_rpm": float(rpm),
            "operating_speed_rpm": float(config["operation"]["speed_rpm"]),
            "configured_hub_thickness_m": float(config["geometry"]["disk"]["hub_thickness"]),
            "configured_crossing_speed_rpm": float(rpm_configured),
            "configured_crossing_frequency_hz": float(hz_configured)}
