"""Structured hexahedral mesh of one blisk sector and its ring sector (docs/design.md §2 "Mesh").

Every block is a tensor grid in logical coordinates mapped to Cartesian space (Z = rotation axis,
the sector centred on the X axis, theta in [-pi/N, pi/N]):

* web   (r, theta, z): bore radius -> contact radius, tapered linearly from hub_thickness at the
  bore to web_thickness under the rim;
* rim   (r, theta, z): contact radius -> blade root radius, |z| <= rim_axial_width / 2;
* arm   (r, theta, z): a thin axial extension of the rim's underside behind it (contact radius ->
  + arm_thickness, z from rim_axial_width / 2 to + arm_length), like the rim arms that carry ring
  dampers (Laxalde et al. 2007); inside the ring's axial band its underside (the groove) follows the
  ring's upper surface, the offset fading linearly to zero at the arm's outer surface;
* blade (r, s, z): a flat plate of constant thickness (s = arc length, theta = s / r), chord along Z
  (zero stagger), root on the rim's outer surface;
* ring  (xi, theta, z): between its lower and upper surfaces (xi = 0 .. 1), a separate body whose
  upper-surface nodes coincide with the groove nodes at rest.

The theta grid has breakpoints at the ends and centres of the lower bumps (-+pi/N, -+2pi/3N,
-+pi/3N) and at the blade faces. Node and element counts never depend on kappa: only radial
coordinates move. The two cyclic faces theta = -+pi/N match node for node through a 2 pi / N
rotation about Z. With 27-node bricks the mesh is isoparametric (scikit-fem ``MeshHex2``): every
node, not only the vertices, is placed by its block's exact map, so cylinders and bumps are exact at
the nodes and a bump's central node moves by exactly its delta_r. With 8-node bricks (``MeshHex1``)
the geometry is trilinear.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.spatial import cKDTree
from skfem import ElementHex1, ElementHex2, MeshHex1, MeshHex2
from skfem.assembly import Dofs

from .shape import lower_offset, shape_offsets, upper_offset

PART_NAMES = ("web", "rim", "blade", "ring", "arm")
PART_WEB, PART_RIM, PART_BLADE, PART_RING, PART_ARM = range(5)
BODY_BLISK, BODY_RING = 0, 1
MERGE_TOL = 1e-9  # m

# scikit-fem MeshHex1 local vertex order, as offsets in the (a, b, c) logical axes
_HEX_CORNERS = np.array([(0, 0, 0), (0, 0, 1), (0, 1, 0), (1, 0, 0),
                         (0, 1, 1), (1, 0, 1), (1, 1, 0), (1, 1, 1)])


@dataclass
class SectorMesh:
    """Vertex mesh of the sector plus the vertex sets the model needs (indices into ``vertices``)."""

    mesh: MeshHex1              # MeshHex2 for 27-node bricks; its first n_vertices nodes are vertices
    vertices: np.ndarray        # (n_vertices, 3)
    part: np.ndarray            # (n_elements,) PART_* of each element
    vertex_body: np.ndarray     # (n_vertices,) BODY_* of each vertex
    kappa: np.ndarray
    deltas: tuple               # (delta1, delta2, delta3) m
    half_angle: float           # pi / N
    sets: dict = field(default_factory=dict)   # name -> vertex indices
    tip_vertex: int = -1        # forcing / response vertex (blade tip, leading edge)

    @property
    def body(self) -> np.ndarray:
        return np.where(self.part == PART_RING, BODY_RING, BODY_BLISK)


def _segment(a: float, b: float, n: int) -> np.ndarray:
    return np.linspace(a, b, n + 1)


def _join(*segments) -> np.ndarray:
    """Concatenate sorted breakpoint arrays that share their end points."""
    out = np.concatenate(segments)
    return np.unique(np.round(out, 15))


def _block(a, b, c, to_xyz):
    """Tensor grid block: points (n, 3) from logical lines a, b, c, hexes (ne, 8), logical coords."""
    A, B, C = np.meshgrid(a, b, c, indexing="ij")
    logical = np.column_stack([A.ravel(), B.ravel(), C.ravel()])
    points = np.column_stack(to_xyz(A.ravel(), B.ravel(), C.ravel()))
    na, nb, nc = len(a), len(b), len(c)
    idx = np.arange(na * nb * nc).reshape(na, nb, nc)
    i, j, k = np.meshgrid(np.arange(na - 1), np.arange(nb - 1), np.arange(nc - 1), indexing="ij")
    hexes = np.stack([idx[i + di, j + dj, k + dk].ravel() for di, dj, dk in _HEX_CORNERS], axis=1)
    return points, hexes, logical


def _cartesian(r, theta, z):
    return r * np.cos(theta), r * np.sin(theta), z


def _trilinear_weights(ref: np.ndarray) -> np.ndarray:
    """(n_ref, 8) trilinear shape functions of the MeshHex1 vertices at reference points."""
    w = np.ones((len(ref), 8))
    for v, corner in enumerate(ElementHex1.doflocs):  # the element's reference vertex positions
        for axis in range(3):
            w[:, v] *= ref[:, axis] if corner[axis] else 1.0 - ref[:, axis]
    return w


def _isoparametric(vertices, hexes, element_logical, element_block, maps) -> MeshHex2:
    """27-node mesh whose nodes are placed by each element's block map (exact geometry at nodes)."""
    linear = MeshHex1(vertices.T.copy(), hexes.T.astype(np.int32).copy())
    dofs = Dofs(linear, ElementHex2())
    weights = _trilinear_weights(ElementHex2.doflocs)             # (27, 8)
    doflocs = np.zeros((3, dofs.N))
    for block, to_xyz in enumerate(maps):
        elems = np.flatnonzero(element_block == block)
        logical = np.einsum("nv,evk->enk", weights, element_logical[elems])  # (e, 27, 3)
        xyz = np.stack(to_xyz(*logical.reshape(-1, 3).T), axis=1).reshape(len(elems), 27, 3)
        doflocs[:, dofs.element_dofs[:, elems].T.ravel()] = xyz.reshape(-1, 3).T
    return MeshHex2(doflocs, linear.t)


def _merge(points: np.ndarray) -> np.ndarray:
    """Representative index (lowest index within MERGE_TOL) for every point."""
    tree = cKDTree(points)
    rep = np.arange(len(points))
    for i, j in sorted(tree.query_pairs(MERGE_TOL)):
        rep[j] = min(rep[j], rep[i])
    return rep[rep]


@dataclass(frozen=True)
class _Frame:
    """The sector's radii (m), angles (rad) and axial positions (m) the blocks are laid out on."""

    th: float           # half sector angle pi / N
    r_bore: float
    r_c: float          # contact radius: the groove's radius at rest
    r_arm: float        # outer surface of the arm
    r_root: float
    r_tip: float
    t_b: float          # blade thickness
    chord: float
    half_w: float       # half the rim's axial width
    web: float          # half the web thickness under the rim
    z_lo: float         # the ring's axial band z_lo .. z_hi
    z_hi: float
    z_arm_end: float    # axial end of the arm

    @classmethod
    def of(cls, g: dict) -> _Frame:
        blade, disk, ring = g["blade"], g["disk"], g["ring"]
        half_w = disk["rim_axial_width"] / 2
        return cls(th=np.pi / g["n_sectors"], r_bore=disk["bore_radius"], r_c=disk["contact_radius"],
                   r_arm=disk["contact_radius"] + disk["arm_thickness"],
                   r_root=blade["tip_radius"] - blade["height"], r_tip=blade["tip_radius"],
                   t_b=blade["thickness"], chord=blade["chord"], half_w=half_w, web=disk["web_thickness"] / 2,
                   z_lo=ring["axial_center"] - ring["width"] / 2, z_hi=ring["axial_center"] + ring["width"] / 2,
                   z_arm_end=half_w + disk["arm_length"])

    def in_band(self, z):
        """True within the ring's axial band (MERGE_TOL included)."""
        return (z >= self.z_lo - MERGE_TOL) & (z <= self.z_hi + MERGE_TOL)


def _block_maps(f: _Frame, disk: dict, ring_thickness: float, deltas: tuple) -> list:
    """(part, map from logical to Cartesian coordinates) of every block, in PART_* order (module docstring)."""
    d1, d2, d3 = deltas

    def arm_map(r, t, z):
        fade = (f.r_arm - r) / (f.r_arm - f.r_c)
        return _cartesian(r + upper_offset(t, f.th, d1) * f.in_band(z) * fade, t, z)

    def ring_map(xi, t, z):
        r_up = f.r_c + upper_offset(t, f.th, d1)
        r_low = f.r_c - ring_thickness + lower_offset(t, f.th, d2, d3)
        return _cartesian(r_low + xi * (r_up - r_low), t, z)

    taper = disk["hub_thickness"] / disk["web_thickness"] - 1.0

    def web_map(r, t, z):
        return _cartesian(r, t, z * (1.0 + taper * (f.r_c - r) / (f.r_c - f.r_bore)))

    def blade_map(r, s, z):
        return _cartesian(r, s / r, z)

    return [(PART_WEB, web_map), (PART_RIM, _cartesian), (PART_BLADE, blade_map), (PART_RING, ring_map),
            (PART_ARM, arm_map)]


def _block_lines(f: _Frame, mcfg: dict) -> dict:
    """part -> its block's logical grid lines (a, b, c) from the ``mesh`` section's counts."""
    th_b = 0.5 * f.t_b / f.r_root
    # breakpoints at the lower bumps' ends and centres (+-th/3, +-2th/3) and at the blade faces
    n3 = mcfg["n_theta_per_third"]
    side = [_segment(f.th / 3, th_b, n3), _segment(2 * f.th / 3, f.th / 3, n3), _segment(f.th, 2 * f.th / 3, n3)]
    theta = _join(*[-seg for seg in side], _segment(-th_b, th_b, mcfg["n_blade_thickness"]), *side)
    z_rim = _join(_segment(-f.half_w, -f.web, mcfg["n_z_front"]), _segment(-f.web, f.web, mcfg["n_z_web"]),
                  _segment(f.web, f.half_w, mcfg["n_z_rim_back"]), [-f.chord / 2, f.chord / 2])
    z_arm = _join(_segment(f.half_w, f.z_lo, mcfg["n_z_gap"]), _segment(f.z_lo, f.z_hi, mcfg["n_z_ring"]),
                  _segment(f.z_hi, f.z_arm_end, mcfg["n_z_back"]))
    r_rim = _join(_segment(f.r_c, f.r_arm, mcfg["n_r_arm"]), _segment(f.r_arm, f.r_root, mcfg["n_r_rim"]))
    z_web = z_rim[(z_rim >= -f.web - MERGE_TOL) & (z_rim <= f.web + MERGE_TOL)]
    z_ring = z_arm[f.in_band(z_arm)]
    z_blade = z_rim[np.abs(z_rim) <= f.chord / 2 + MERGE_TOL]
    s_blade = _segment(-f.t_b / 2, f.t_b / 2, mcfg["n_blade_thickness"])
    return {
        PART_WEB: (_segment(f.r_bore, f.r_c, mcfg["n_r_web"]), theta, z_web),
        PART_RIM: (r_rim, theta, z_rim),
        PART_ARM: (_segment(f.r_c, f.r_arm, mcfg["n_r_arm"]), theta, z_arm),
        PART_BLADE: (_segment(f.r_root, f.r_tip, mcfg["n_blade_height"]), s_blade, z_blade),
        PART_RING: (_segment(0.0, 1.0, mcfg["n_r_ring"]), theta, z_ring),
    }


def _stack_blocks(blocks: list):
    """The blocks' ``(part, (points, hexes, logical))`` in one numbering: points, hexes, the part of each
    element, the logical coordinates and the owning part of each point."""
    points, hexes, parts, logicals, owners = [], [], [], [], []
    offset = 0
    for part, (p, h, lg) in blocks:
        points.append(p)
        hexes.append(h + offset)
        parts.append(np.full(len(h), part))
        logicals.append(lg)
        owners.append(np.full(len(p), part))
        offset += len(p)
    return np.vstack(points), np.vstack(hexes), np.concatenate(parts), np.vstack(logicals), np.concatenate(owners)


def _merge_blisk(points, hexes, logical, owner):
    """Merge coincident vertices inside the blisk only (the ring stays a separate body): the points,
    hexes, logical coordinates and owners renumbered."""
    rep = np.arange(len(points))
    blisk = np.flatnonzero(owner != PART_RING)
    rep[blisk] = blisk[_merge(points[blisk])]
    used, new_index = np.unique(rep, return_inverse=True)
    return points[used], new_index[hexes], logical[used], owner[used]


def _vertex_sets(f: _Frame, points, logical, owner) -> tuple[dict, int]:
    """The named vertex sets (bore, cyclic faces left/right, ring top, groove) and the tip vertex (blade
    tip, leading edge, suction side)."""
    r = np.hypot(points[:, 0], points[:, 1])
    ang = np.arctan2(points[:, 1], points[:, 0])
    is_ring = owner == PART_RING
    sets = {
        "bore": np.flatnonzero(~is_ring & (np.abs(r - f.r_bore) < MERGE_TOL)),
        "left": np.flatnonzero(np.abs(ang + f.th) < 1e-12),
        "right": np.flatnonzero(np.abs(ang - f.th) < 1e-12),
        "ring_top": np.flatnonzero(is_ring & (np.abs(logical[:, 0] - 1.0) < 1e-12)),
        "groove": np.flatnonzero((owner == PART_ARM) & (np.abs(logical[:, 0] - f.r_c) < MERGE_TOL)
                                 & f.in_band(points[:, 2])),
    }
    tip = np.flatnonzero((owner == PART_BLADE) & (np.abs(logical[:, 0] - f.r_tip) < MERGE_TOL)
                         & (np.abs(logical[:, 1] + f.t_b / 2) < MERGE_TOL)
                         & (np.abs(points[:, 2] + f.chord / 2) < MERGE_TOL))
    return sets, int(tip[0])


def build_sector(config: dict, kappa) -> SectorMesh:
    """Mesh the sector for shape ``kappa`` with the geometry and mesh sections of ``config``."""
    g, mcfg = config["geometry"], config["mesh"]
    kappa = np.asarray(kappa, dtype=float)
    deltas = shape_offsets(kappa, g["shape"])
    f = _Frame.of(g)
    maps = _block_maps(f, g["disk"], g["ring"]["thickness"], deltas)
    lines = _block_lines(f, mcfg)
    points, hexes, element_part, logical, owner = _stack_blocks(
        [(part, _block(*lines[part], to_xyz)) for part, to_xyz in maps])
    element_logical = logical[hexes]  # (e, 8, 3), before merging: each element in its own block
    points, hexes, logical, owner = _merge_blisk(points, hexes, logical, owner)
    if mcfg["element_order"] == 2:
        mesh = _isoparametric(points, hexes, element_logical, element_part, [to_xyz for _, to_xyz in maps])
    else:
        mesh = MeshHex1(points.T.copy(), hexes.T.astype(np.int32).copy())
    sets, tip = _vertex_sets(f, points, logical, owner)
    return SectorMesh(mesh=mesh, vertices=points, part=element_part,
                      vertex_body=np.where(owner == PART_RING, BODY_RING, BODY_BLISK), kappa=kappa,
                      deltas=tuple(deltas), half_angle=f.th, sets=sets, tip_vertex=tip)
