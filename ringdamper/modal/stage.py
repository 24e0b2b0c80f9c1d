"""Modal stage of the campaign (paper §2.3): ND diagram, Campbell diagram and the selected resonance.

Run once on the default ring. The contact is linearised from the static contact state: pairs with
N0 > 0 stuck (kn, kt springs), pairs with an open gap free; without a static state every pair is
taken as stuck (the stuck linearisation of ``fem.contact_law``). The datasets say which in their
``contact_state`` attribute. The ND diagram's normalised frequency is 2.195 f / f_cross
(docs/design.md §2, *Frequency normalisation*), with f_cross the FE model's target-mode frequency at
the crossing speed (``reference_frequency_hz``); the dNNM stage normalises by the reduced model's
stuck frequency instead (``modal/stuck_default.yaml``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import xarray as xr

from ringdamper.fem.model import SectorModel, build_model, stuck_contact_stiffness
from ringdamper.fem.prestress import prestressed_stiffness, rpm_to_rad_s
from ringdamper.geometry.sector import build_sector
from ringdamper.io import variable
from ringdamper.modal.analysis import (
    FamilyClassifier,
    campbell,
    cyclic_modes,
    eo_crossing,
    family_frequency,
    labelled_modes,
)
from ringdamper.nonlinear.normalisation import normalised_frequency

NO_STATIC_STATE = "all pairs stuck (linearised kn, kt springs): static contact state not used"


@dataclass
class ModalResults:
    model: SectorModel
    nd_diagram: xr.Dataset
    campbell: xr.Dataset
    resonance: dict
    K_operating: object


def linearised_contact(model: SectorModel, contact_cfg: dict, in_contact=None):
    """Stuck linearisation of the contact on the closed pairs, and a description."""
    closed = np.ones(len(model.pairs), bool) if in_contact is None else np.asarray(in_contact, bool)
    Kc = stuck_contact_stiffness(model, contact_cfg, closed)
    state = (NO_STATIC_STATE if in_contact is None else
             f"static contact state: {int(closed.sum())} of {len(closed)} pairs stuck (N0 > 0), "
             "the others free")
    return Kc, state


def run_modal_stage(config: dict, in_contact=None) -> ModalResults:
    """Modal stage; ``in_contact`` (per pair) from the default ring's static state, if available."""
    modal, op = config["modal"], config["operation"]
    model = build_model(build_sector(config, (0.0, 0.0, 0.0)), config)
    Kc, contact_state = linearised_contact(model, config["contact"], in_contact)
    omega_op = rpm_to_rad_s(op["speed_rpm"])
    clf = FamilyClassifier(model)

    speeds = np.linspace(0.0, modal["campbell_speed_factor"] * omega_op, modal["campbell_n_speeds"])
    c_freq, c_lab = campbell(model, Kc, speeds, modal["target_nd"], modal["n_modes"])
    family = np.array([family_frequency(f, lab, modal["target_family"]) for f, lab in zip(c_freq, c_lab)])
    w_cross, f_cross = eo_crossing(speeds, family, op["engine_order"])
    K_op = prestressed_stiffness(model, omega_op, Kc)
    reference_hz = f_cross

    nds = np.arange(modal["nd_max"] + 1)
    rows = [labelled_modes(model, K_op, int(nd), modal["n_modes"], clf) for nd in nds]
    freq = np.array([r[0] for r in rows])
    labels = np.array([r[1] for r in rows], dtype=str)
    blade = np.array([r[2] for r in rows])

    attrs = {"speed_rpm": op["speed_rpm"], "contact_state": contact_state,
             "element_order": model.element_order, "dofs": model.n_dofs,
             "reference_frequency_hz": reference_hz}
    coords_nd = {"nd": variable("nd", nds, "1", "nodal diameter"),
                 "mode": variable("mode", np.arange(modal["n_modes"]), "1", "mode index within the ND")}
    nd_ds = xr.Dataset(
        {"frequency": variable(("nd", "mode"), freq, "Hz", "natural frequency at operating speed"),
         "omega0": variable(("nd", "mode"), normalised_frequency(freq, reference_hz), "1",
                            "normalised frequency 2.195 f / f_cross, f_cross the target mode's frequency "
                            "at the engine-order crossing (reference_frequency_hz)"),
         "family": variable(("nd", "mode"), labels, "1", "mode family (1B, 1T, 2B, 1D, 2D, ...)"),
         "blade_energy_fraction": variable(("nd", "mode"), blade, "1",
                                           "fraction of the strain energy in the blade")},
        coords=coords_nd, attrs=attrs)
    camp_ds = xr.Dataset(
        {"frequency": variable(("speed", "mode"), c_freq, "Hz", "natural frequency"),
         "family": variable(("speed", "mode"), np.asarray(c_lab, dtype=str), "1", "mode family")},
        coords={"speed": variable("speed", speeds * 60 / (2 * np.pi), "rpm", "rotation speed"),
                "mode": coords_nd["mode"]},
        attrs={**attrs, "nd": modal["target_nd"], "engine_order": op["engine_order"]})
    resonance = {
        "engine_order": op["engine_order"], "nd": modal["target_nd"], "family": modal["target_family"],
        "speed_rpm": float(w_cross * 60 / (2 * np.pi)), "frequency_hz": float(f_cross),
        "operating_speed_rpm": op["speed_rpm"],
        "relative_speed_offset": float(w_cross / omega_op - 1.0),
        "contact_state": contact_state,
    }
    return ModalResults(model=model, nd_diagram=nd_ds, campbell=camp_ds, resonance=resonance,
                        K_operating=K_op)


def target_mode_shapes(results: ModalResults, config: dict, n: int = 4):
    """(frequency, family, real displacement (n_nodes, 3)) of the first ``n`` modes of the target ND."""
    modal = config["modal"]
    model = results.model
    modes = cyclic_modes(model, results.K_operating, model.M, modal["target_nd"], n)
    fam = results.nd_diagram.family.sel(nd=modal["target_nd"]).values
    out = []
    for j in range(n):
        phi = modes.shapes[:, j]
        phi = phi * np.exp(-1j * np.angle(phi[np.argmax(np.abs(phi))]))
        out.append((modes.frequency[j], str(fam[j]), np.real(phi).reshape(-1, 3)))
    return out
