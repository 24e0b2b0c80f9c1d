"""Mesh convergence of the target mode (docs/design.md §6: every approximation is a dial with a chart).

A mesh level multiplies every element count of the ``mesh`` section; for each level the 1D-ND3
frequency of the default ring is computed at operating speed (prestressed, contact stuck), with the
model size and wall time, so that the default can be placed on the cost-accuracy curve.
"""

from __future__ import annotations

import copy
import time

from ringdamper.fem.model import build_model, stuck_contact_stiffness
from ringdamper.fem.prestress import prestressed_stiffness, rpm_to_rad_s
from ringdamper.geometry.sector import build_sector
from ringdamper.modal.analysis import FamilyClassifier, family_frequency, labelled_modes

COUNT_KEYS = ("n_theta_per_third", "n_r_web", "n_r_rim", "n_r_arm", "n_r_ring", "n_z_front", "n_z_web",
              "n_z_rim_back", "n_z_gap", "n_z_ring", "n_z_back", "n_blade_height", "n_blade_thickness")


def refined(config: dict, factor: int, element_order: int | None = None) -> dict:
    """Copy of ``config`` with every mesh count multiplied by ``factor``."""
    out = copy.deepcopy(config)
    for key in COUNT_KEYS:
        out["mesh"][key] *= factor
    if element_order is not None:
        out["mesh"]["element_order"] = element_order
    return out


def family_frequencies(config: dict, families) -> dict:
    """Frequencies (Hz) of the first mode of each family at the target ND, at operating speed
    (prestressed, contact stuck), with the model size and wall time (``frequency_<family>``)."""
    start = time.perf_counter()
    model = build_model(build_sector(config, (0.0, 0.0, 0.0)), config)
    K = prestressed_stiffness(model, rpm_to_rad_s(config["operation"]["speed_rpm"]),
                              stuck_contact_stiffness(model, config["contact"]))
    modal = config["modal"]
    f, labels, _ = labelled_modes(model, K, modal["target_nd"], modal["n_modes"], FamilyClassifier(model))
    return {"dofs": model.n_dofs, "elements": int(model.geometry.mesh.t.shape[1]), "pairs": len(model.pairs),
            **{f"frequency_{fam}": float(family_frequency(f, labels, fam)) for fam in families},
            "wall_time_s": time.perf_counter() - start}


def target_frequency(config: dict) -> dict:
    """Frequency (Hz) of the target family/ND at operating speed, with the model size and wall time."""
    row = family_frequencies(config, [config["modal"]["target_family"]])
    row["frequency_hz"] = row.pop(f"frequency_{config['modal']['target_family']}")
    return row


def mesh_study(config: dict, levels) -> list[dict]:
    """(refinement factor, element order) ``levels`` (``studies.mesh_convergence.levels`` of the
    configuration); errors relative to the finest quadratic level."""
    rows = [dict(order=order, factor=factor, **target_frequency(refined(config, factor, order)))
            for factor, order in levels]
    reference = max((r for r in rows if r["order"] == 2), key=lambda r: r["dofs"])["frequency_hz"]
    for r in rows:
        r["relative_error"] = abs(r["frequency_hz"] - reference) / reference
    return rows
