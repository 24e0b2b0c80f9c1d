"""Static contact stage (paper §2.4, §3.1.2; docs/design.md §3.2): N0 and gap of every contact pair.

The sector (blisk + ring, linear elastic) is solved at operating speed with the ND-0 cyclic
constraint u_R = R_z(2 pi / N) u_L (``fem.cyclic``), the bore clamped, the centrifugal body force
f = rho Omega^2 (x, y, 0) and the spin softening -Omega^2 M_r (the centrifugal force follows the
displaced material). Contact: one node-to-node pair per ring upper-surface node, initial gap from the ring's nominal
radial clearance (``geometry.ring.radial_clearance``, :func:`clearance_gaps`), normal law of
``static.method`` (penalty kn x area: the law of the dynamic element, so N0 is consistent with it;
or exact unilateral contact), tangential sticking springs kt x area that make the ring's rotation
about Z and its axial translation determinate. Geometric nonlinearity is neglected: the strains are
~1e-4 and the static problem is only needed for the contact state.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import xarray as xr

from ringdamper.fem.contact_law import pair_stiffness
from ringdamper.fem.cyclic import cyclic_transform, project
from ringdamper.fem.elasticity import centrifugal_load
from ringdamper.fem.model import SectorModel, build_model, node_dofs, relative_displacement_operator
from ringdamper.fem.prestress import rpm_to_rad_s, spin_mass
from ringdamper.geometry.sector import BODY_RING, build_sector
from ringdamper.io import declared_dataset, nan_values, variable
from ringdamper.static.solver import StaticContactResult, solve_static_contact

log = logging.getLogger(__name__)


@dataclass
class StaticProblem:
    """ND-0 sector matrices reduced to the independent DoFs, and the contact data."""

    K: sp.csr_matrix
    f: np.ndarray
    G: sp.csr_matrix
    T: sp.csr_matrix
    kn: np.ndarray
    kt: np.ndarray
    g0: np.ndarray


def clearance_gaps(model: SectorModel, clearance: float) -> np.ndarray:
    """Initial gap of every pair (m) for a nominal radial clearance ``clearance`` (groove radius minus
    ring radius at rest): the ring shrunk radially by c leaves the gap g0 = c (n . e_r) along each
    pair's normal n. The mesh keeps coincident pair nodes: c (tens of um) is small beside the
    elements (mm), as the small-displacement contact frames already assume."""
    p = model.pairs.position[:, :2]
    e_r = p / np.linalg.norm(p, axis=1)[:, None]
    return clearance * np.sum(model.pairs.frame[:, 0, :2] * e_r, axis=1)


def static_problem(model: SectorModel, config: dict, speed_rpm: float,
                   rigid_blisk: bool = False) -> StaticProblem:
    """Assemble the ND-0 static contact problem (``rigid_blisk`` clamps the whole blisk: an oracle)."""
    omega = rpm_to_rad_s(speed_rpm)
    fixed = model.fixed_dofs
    if rigid_blisk:
        fixed = np.union1d(fixed, node_dofs(np.flatnonzero(model.node_body != BODY_RING)))
    T, _ = cyclic_transform(model.n_dofs, model.left_nodes, model.right_nodes, fixed,
                            model.sector_angle, 0.0)
    K = project(T, model.K - omega**2 * spin_mass(model))
    f = T.T @ centrifugal_load(model.basis, model.material["density"], omega)
    G = (relative_displacement_operator(model) @ T).tocsr()
    kn, kt = pair_stiffness(model.pairs.area, config["contact"])
    g0 = clearance_gaps(model, config["geometry"]["ring"]["radial_clearance"])
    return StaticProblem(K=K, f=f, G=G, T=T, kn=kn, kt=kt, g0=g0)


def solve_static(model: SectorModel, config: dict, speed_rpm: float | None = None,
                 rigid_blisk: bool = False, kn=None, g0=None) -> tuple[StaticContactResult, StaticProblem]:
    """Solve the static contact problem; ``kn`` and ``g0`` (per pair, m) override the configured
    normal stiffness and the initial gaps of the configured clearance."""
    speed = config["operation"]["speed_rpm"] if speed_rpm is None else speed_rpm
    prob = static_problem(model, config, speed, rigid_blisk)
    if kn is not None:
        prob.kn = np.broadcast_to(np.asarray(kn, dtype=float), prob.kn.shape).copy()
    if g0 is not None:
        prob.g0 = np.broadcast_to(np.asarray(g0, dtype=float), prob.g0.shape).copy()
    return solve_problem(prob, config["static"]), prob


def substructured_problem(model: SectorModel, split, se, config: dict,
                          speed_rpm: float | None = None) -> StaticProblem:
    """The ND-0 static problem of the morph zone ``model`` (``build_model(..., elements=)``) on the
    static super-element ``se`` (``reduction.superelement``): the monolithic problem with the fixed
    part condensed exactly, on the morph zone's independent coordinates."""
    from ringdamper.reduction.substructured import coupled_static, sector_transform

    speed = config["operation"]["speed_rpm"] if speed_rpm is None else speed_rpm
    prob = static_problem(model, config, speed)
    _, independent = sector_transform(model, 0.0)
    prob.K, prob.f, keep = coupled_static(prob.K, prob.f, se, model, split, prob.T, independent)
    prob.G, prob.T = prob.G[:, keep].tocsr(), prob.T[:, keep].tocsr()
    return prob


def solve_problem(prob: StaticProblem, settings: dict) -> StaticContactResult:
    """Solve an assembled problem with the ``static:`` settings (method, tolerance, max_iterations)."""
    return solve_static_contact(prob.K, prob.f, prob.G, prob.g0, prob.kn, prob.kt, method=settings["method"],
                                tol=settings["tolerance"], max_iter=settings["max_iterations"])


#: static.nc, declared once: name -> (dims, units, long_name). A failed geometry's file has the same
#: variables, all NaN (in_contact -1), and the same attributes.
STATIC_VARIABLES = {
    "x": ("pair", "m", "pair position x (at rest)"),
    "y": ("pair", "m", "pair position y (at rest)"),
    "z": ("pair", "m", "pair position z (at rest)"),
    "N0": ("pair", "N", "static normal contact force (preload)"),
    "gap": ("pair", "m", "static normal gap"),
    "penetration": ("pair", "m", "penalty penetration"),
    "initial_gap": ("pair", "m", "normal gap at rest (radial clearance)"),
    "in_contact": ("pair", "1", "1 if N0 > 0, 0 if not, -1 without a solution"),
    "tangential_force": (("pair", "direction"), "N",
                         "static tangential force of the sticking springs (t1, t2)"),
    "area": ("pair", "m2", "tributary contact area"),
    "pressure": ("pair", "Pa", "static contact pressure N0 / area"),
    "frame": (("pair", "direction", "component"), "1",
              "local frame: rows n (ring to blisk), t1 (circumferential), t2 (axial)"),
    "kn": ("pair", "N m-1", "normal contact stiffness"),
    "kt": ("pair", "N m-1", "tangential contact stiffness"),
}


def static_file(n_pairs: int, values: dict, attrs: dict) -> xr.Dataset:
    """static.nc from its arrays: ``values`` holds exactly the variables of :data:`STATIC_VARIABLES`."""
    coords = {"pair": variable("pair", np.arange(n_pairs), "1", "contact pair index"),
              "direction": variable("direction", ["n", "t1", "t2"], "1", "local frame axis"),
              "component": variable("component", ["x", "y", "z"], "1", "Cartesian component")}
    return declared_dataset("static.nc", STATIC_VARIABLES, values, coords, attrs)


def static_dataset(model: SectorModel, result: StaticContactResult, prob: StaticProblem,
                   kappa, speed_rpm: float) -> xr.Dataset:
    """``static.nc`` (docs/design.md §4): per pair N0, gap, in_contact, position, frame; KKT in the attrs."""
    pairs = model.pairs
    m = len(pairs)
    finite = np.all(np.isfinite(result.N0))
    values = {
        "x": pairs.position[:, 0], "y": pairs.position[:, 1], "z": pairs.position[:, 2],
        "N0": result.N0, "gap": result.gap, "penetration": result.penetration, "initial_gap": prob.g0,
        "in_contact": result.in_contact.astype(np.int8),
        "tangential_force": (np.column_stack([np.zeros(m), result.tangential]) if finite
                             else np.full((m, 3), np.nan)),
        "area": pairs.area, "pressure": result.N0 / pairs.area, "frame": pairs.frame,
        "kn": prob.kn, "kt": prob.kt,
    }
    attrs = {"kappa": np.asarray(kappa, dtype=float), "speed_rpm": float(speed_rpm),
             "method": result.method, "iterations": int(result.iterations),
             "equilibrium_residual": float(result.residual),
             "complementarity_residual": float(result.complementarity),
             "status": int(result.status), "reason": result.reason,
             "n_in_contact": int(np.sum(result.in_contact)) if finite else -1}
    return static_file(m, values, attrs)


def failed_static(config: dict, kappa, reason: str, n_pairs: int) -> xr.Dataset:
    """static.nc of a geometry whose stage raised: the variables and attributes of a solved one, all
    NaN (in_contact -1; no pair when no mesh was built), status 99 and the ``reason``."""
    values = nan_values(STATIC_VARIABLES, {"pair": n_pairs, "direction": 3, "component": 3})
    values["in_contact"] = np.full(n_pairs, -1, dtype=np.int8)
    attrs = {"kappa": np.asarray(kappa, dtype=float), "speed_rpm": float(config["operation"]["speed_rpm"]),
             "method": config["static"]["method"], "iterations": -1, "equilibrium_residual": np.nan,
             "complementarity_residual": np.nan, "status": 99, "reason": reason, "n_in_contact": -1}
    return static_file(n_pairs, values, attrs)


def static_fields(model: SectorModel, result: StaticContactResult | None = None,
                  prob: StaticProblem | None = None) -> dict:
    """Point fields for ParaView: displacement, and N0 / gap of the pair weighing each node most; NaN where
    the solve gave no value (no ``result``, or a non-finite solution)."""
    n = len(model.nodes)
    n0 = np.full(n, np.nan if result is None else 0.0)
    gap = n0.copy()
    if result is not None:
        pair = model.pairs.pair_of_node(n)
        read = pair >= 0
        n0[read] = result.N0[pair[read]]
        gap[read] = result.gap[pair[read]]
    solved = result is not None and np.all(np.isfinite(result.u))
    u = (prob.T @ result.u).reshape(-1, 3) if solved else np.full((n, 3), np.nan)
    return {"displacement": u, "N0": n0, "gap": gap}


def _ring_model(config: dict, kappa, superelement):
    """(model, substructure): the whole sector's model, or with a super-element file the morph
    zone's and (split, super-element)."""
    if superelement is None:
        return build_model(build_sector(config, kappa), config), None
    from ringdamper.reduction.substructured import morph_model
    from ringdamper.reduction.superelement import load

    se = load(superelement)
    model, split = morph_model(config, kappa, se, superelement)
    return model, (split, se)


def _solve(model: SectorModel, config: dict, substructure) -> tuple[StaticContactResult, StaticProblem]:
    if substructure is None:
        return solve_static(model, config)
    prob = substructured_problem(model, *substructure, config)
    return solve_problem(prob, config["static"]), prob


def _morph_fields(fields: dict, model: SectorModel, split) -> dict:
    """The displacement NaN outside the morph zone (the fixed part's interior is condensed)."""
    outside = np.ones(len(model.nodes), dtype=bool)
    outside[np.unique(model.basis.dofs.element_dofs[:, split.morph_elements])] = False
    fields["displacement"][outside] = np.nan
    return fields


def run_static(config: dict, kappa, superelement=None) -> tuple[xr.Dataset, SectorModel | None, dict | None]:
    """The static stage of geometry ``kappa`` at the operating speed: (static.nc dataset, model,
    static.vtu point fields), monolithic or, with ``superelement`` (a file of
    ``reduction.superelement``), on the fixed substructure (the displacement field then covers the
    morph zone only: NaN elsewhere). It never raises: a failure (meshing, assembly or solve) gives
    :func:`failed_static` (status 99 and the reason); the model and its fields, all NaN, when the mesh was
    built, else no model nor fields, so the campaign goes on."""
    model = None
    try:
        model, substructure = _ring_model(config, kappa, superelement)
        result, prob = _solve(model, config, substructure)
    except Exception as err:  # a failed geometry must not stop the campaign
        log.exception("static stage failed for kappa=%s", list(kappa))
        return (failed_static(config, kappa, f"{type(err).__name__}: {err}",
                              0 if model is None else len(model.pairs)),
                model, None if model is None else static_fields(model))
    ds = static_dataset(model, result, prob, kappa, config["operation"]["speed_rpm"])
    log.info("kappa=%s status=%d (%s) iterations=%d in_contact=%d/%d residual=%.2e "
             "complementarity=%.2e", list(kappa), result.status, result.reason, result.iterations,
             ds.attrs["n_in_contact"], len(model.pairs), result.residual, result.complementarity)
    fields = static_fields(model, result, prob)
    return ds, model, fields if substructure is None else _morph_fields(fields, model, substructure[0])
