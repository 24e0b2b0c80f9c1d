"""The fixed substructure, reduced once per campaign: its super-elements and their file.

The sector splits (``geometry.split``) into the fixed part (the blisk outside the morph zone, the
same in every ring) and the morph zone (the ring and the rim arm's elements whose groove follows
kappa). The fixed part's K, M, spin-softening mass M_r and centrifugal load are assembled on its
elements alone (``fem.model.build_model(..., elements=)``) and, per phase sigma, projected
cyclically first with the whole sector's transform, A(sigma) = T(sigma)^H A T(sigma) (``fem.cyclic``:
the right face is eliminated before anything dense exists). In those independent coordinates the
super-element's boundary b is

* every independent DoF that both the fixed part and the morph zone touch (the interface nodes, a
  right-face interface node through its left partner), and
* the blade-tip response node's DoFs (the forcing and response coordinate, kept physical),

and its interior i the fixed part's other DoFs. Two super-elements per campaign
(:func:`~ringdamper.reduction.hermitian_cb.condense`):

* **static** (ND 0 at the operating speed): Guyan's, exact, of K - Omega^2 M_r with the centrifugal
  load f condensed, f_b + Psi^T f_i;
* **per harmonic h** (phase sigma_h of ``fem.cyclic.interblade_phase``): Craig–Bampton of (K, M)
  with ``substructure.n_modes`` fixed-interface modes.

Prestress: the monolithic chain's, no other. The static stage has spin softening -Omega^2 M_r and
the centrifugal load and no stress stiffening; the reduction is linear elastic at rest. So the
static super-element is exact and the harmonic ones approximate only by the truncation of the fixed
part's modes.

The file (``.npz``, :func:`save` / :func:`load`): ``boundary`` (global DoF indices 3a + c),
``static_K`` (N m-1), ``static_f`` (N), per harmonic ``K_<h>`` (N m-1, b block, then the modal
block rad2 s-2 on the diagonal), ``M_<h>`` (kg on the b block, kg1/2 b-to-mode, 1 on the modes),
``omega2_<h>`` (rad2 s-2), ``sigma`` (rad), ``harmonics``, and the checks ``fixed_positions_sha256``
(the fixed part's node coordinates) and ``config_sha256`` (the blisk sections it was built from).
"""

from __future__ import annotations

import hashlib
import json
import time
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from ..fem.cyclic import cyclic_transform, interblade_phase, project
from ..fem.elasticity import centrifugal_load
from ..fem.model import SectorModel, build_model, node_dofs
from ..fem.prestress import rpm_to_rad_s, spin_mass
from ..geometry.sector import build_sector
from ..geometry.split import SectorSplit, split_sector
from .hermitian_cb import condense

#: What the fixed part depends on: the configuration sections and keys a super-element is built from
#: (the ring's axial band places the groove in the arm's mesh; its radial thickness and clearance
#: move only the ring). The workflow passes exactly these as the rule's params.
BLISK_SECTIONS = ("material", "mesh", "operation", "geometry.n_sectors", "geometry.blade",
                  "geometry.disk", "geometry.shape", "reduction.n_harmonics",
                  "substructure.n_modes")
BLISK_RING_KEYS = ("width", "axial_center")


def blisk_config(config: dict) -> dict:
    """The part of ``config`` the fixed substructure depends on (:data:`BLISK_SECTIONS` without the
    contact pairs, which live in the morph zone, and the ring's axial band), keys sorted."""
    out: dict = {}
    for name in BLISK_SECTIONS:
        section, _, key = name.partition(".")
        if section not in config or (key and key not in config[section]):
            continue    # a configuration without substructuring: the rule cannot run
        if key:
            out.setdefault(section, {})[key] = config[section][key]
        else:
            out[section] = config[section]
    out["geometry"]["ring"] = {k: config["geometry"]["ring"][k] for k in BLISK_RING_KEYS}
    out["mesh"] = {k: v for k, v in out["mesh"].items() if k != "contact_pairs"}   # pairs: morph zone only
    return json.loads(json.dumps(out, sort_keys=True))


def config_hash(config: dict) -> str:
    """SHA-256 of the canonical JSON of :func:`blisk_config`."""
    text = json.dumps(blisk_config(config), sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(text.encode()).hexdigest()


def fixed_positions_hash(model: SectorModel, split: SectorSplit) -> str:
    """SHA-256 of the coordinates of the fixed part's nodes (the same, bit for bit, for every ring)."""
    nodes = np.unique(model.basis.dofs.element_dofs[:, split.fixed_elements])
    return hashlib.sha256(np.ascontiguousarray(model.nodes[nodes]).tobytes()).hexdigest()


@dataclass
class SuperElement:
    boundary: np.ndarray          # global DoFs of the b coordinates (independent, sorted)
    static_K: np.ndarray          # (n_b, n_b) N/m
    static_f: np.ndarray          # (n_b,) N
    harmonics: np.ndarray         # h of each harmonic super-element
    sigma: np.ndarray             # rad
    K: list                       # per harmonic (n_b + n_s)^2
    M: list
    omega2: list                  # per harmonic (n_s,)
    fixed_positions_sha256: str
    config_sha256: str
    cpu_s: dict = field(default_factory=dict)


def touched(T: sp.csr_matrix, dofs: np.ndarray) -> np.ndarray:
    """Independent coordinates (columns of T) that the global ``dofs`` depend on."""
    return np.unique(T[dofs].indices)


def coordinates(model: SectorModel, split: SectorSplit, T: sp.csr_matrix):
    """(boundary, fixed interior, morph zone) positions among T's independent coordinates."""
    element_nodes = model.basis.dofs.element_dofs
    fixed = touched(T, node_dofs(np.unique(element_nodes[:, split.fixed_elements])))
    morph = touched(T, node_dofs(np.unique(element_nodes[:, split.morph_elements])))
    tip = touched(T, node_dofs([model.tip_node]))
    boundary = np.union1d(np.intersect1d(fixed, morph), tip)
    return boundary, np.setdiff1d(fixed, boundary), np.union1d(morph, boundary)


def sector_transform(model: SectorModel, sigma: float):
    return cyclic_transform(model.n_dofs, model.left_nodes, model.right_nodes, model.fixed_dofs,
                            model.sector_angle, sigma)


def build_superelement(config: dict) -> SuperElement:
    """The fixed part of ``config``'s sector reduced: the static and every harmonic's super-element."""
    c0 = time.process_time()
    split = split_sector(config)
    fixed = build_model(build_sector(config, (0.0, 0.0, 0.0)), config, elements=split.fixed_elements)
    c1 = time.process_time()
    omega = rpm_to_rad_s(config["operation"]["speed_rpm"])
    T0, independent = sector_transform(fixed, 0.0)
    b, i, _ = coordinates(fixed, split, T0)
    load = T0.T @ centrifugal_load(fixed.basis, fixed.material["density"], omega)
    static = condense(project(T0, fixed.K - omega**2 * spin_mass(fixed)), None, b, i, f=load)
    c2 = time.process_time()
    harmonics = np.arange(config["reduction"]["n_harmonics"] + 1)
    eo = config["operation"]["engine_order"]
    sigma = np.array([interblade_phase(h, fixed.n_sectors, eo) for h in harmonics])
    n_s = config["substructure"]["n_modes"]
    K, M, w2 = [], [], []
    for s in sigma:
        T = sector_transform(fixed, s)[0]
        cb = condense(project(T, fixed.K), project(T, fixed.M), b, i, n_s)
        K.append(cb.K)
        M.append(cb.M)
        w2.append(cb.omega2)
    cpu = {"assembly": c1 - c0, "static": c2 - c1, "harmonics": time.process_time() - c2}
    return SuperElement(boundary=independent[b], static_K=static.K, static_f=static.f,
                        harmonics=harmonics, sigma=sigma, K=K, M=M, omega2=w2,
                        fixed_positions_sha256=fixed_positions_hash(fixed, split),
                        config_sha256=config_hash(config), cpu_s=cpu)


def save(se: SuperElement, path) -> None:
    """The super-element as ``.npz`` (arrays of the module docstring), written whole or not at all."""
    from ..io import written_whole

    arrays = {"boundary": se.boundary, "static_K": se.static_K, "static_f": se.static_f,
              "harmonics": se.harmonics, "sigma": se.sigma,
              "fixed_positions_sha256": np.array(se.fixed_positions_sha256),
              "config_sha256": np.array(se.config_sha256),
              "cpu_s": np.array(json.dumps(se.cpu_s))}
    for h, k, m, w in zip(se.harmonics, se.K, se.M, se.omega2):
        arrays.update({f"K_{h}": k, f"M_{h}": m, f"omega2_{h}": w})
    with written_whole(path) as part:
        with open(part, "wb") as out:
            np.savez(out, **arrays)


def load(path) -> SuperElement:
    with np.load(path) as z:
        hs = z["harmonics"]
        return SuperElement(boundary=z["boundary"], static_K=z["static_K"], static_f=z["static_f"],
                            harmonics=hs, sigma=z["sigma"], K=[z[f"K_{h}"] for h in hs],
                            M=[z[f"M_{h}"] for h in hs], omega2=[z[f"omega2_{h}"] for h in hs],
                            fixed_positions_sha256=str(z["fixed_positions_sha256"]),
                            config_sha256=str(z["config_sha256"]), cpu_s=json.loads(str(z["cpu_s"])))


def superelement_path(rule_input) -> str | None:
    """The super-element file among a rule's named inputs (``superelement``), None without one."""
    paths = getattr(rule_input, "superelement", [])
    paths = [paths] if isinstance(paths, str) else list(paths)
    return paths[0] if paths else None
