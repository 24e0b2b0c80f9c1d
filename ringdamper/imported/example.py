"""An example blisk sector that is not the built-in one, made with Gmsh: its own blade count, radii
and a staggered blade, second-order tetrahedra, written as a Gmsh 4.1 mesh and a flat Abaqus deck
with the sets an import needs (docs/imported.md).

The sector's (r, z) profile (web, rim and a rim arm behind it whose underside is the groove) is
revolved by 2 pi / N about Z; a flat blade plate, rotated by the stagger angle about its radial
axis, is fragmented with it (conforming meshes of disk and blade, the blade its own volume). The high
cyclic face is meshed as the low one rotated by +2 pi / N (Gmsh's periodic meshing), so the faces
match node for node. Mid-edge nodes are placed at the straight edges' midpoints
(Mesh.SecondOrderLinear): straight-sided tetrahedra, whose matrices every code integrates exactly.

    python -m ringdamper.imported.example OUT_FOLDER [--size 0.008]
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

EXAMPLE = {
    "n_sectors": 24, "bore_radius": 0.060, "contact_radius": 0.120, "rim_radius": 0.135,
    "web_thickness": 0.012, "rim_width": 0.030, "arm_thickness": 0.004, "arm_length": 0.015,
    "tip_radius": 0.190, "chord": 0.025, "blade_thickness": 0.0025, "stagger_deg": 30.0,
}
SETS = {"fixed": "BORE", "cyclic_low": "CYC_LOW", "cyclic_high": "CYC_HIGH", "groove": "GROOVE",
        "forcing": "FORCING", "blade": "BLADE"}


def _profile(occ, g):
    """The (r, z) profile in the x-z plane, the groove's generating line split off."""
    rb, rc, rr = g["bore_radius"], g["contact_radius"], g["rim_radius"]
    tw, w, ta, arm = g["web_thickness"] / 2, g["rim_width"] / 2, g["arm_thickness"], g["arm_length"]
    corners = [(rb, -tw), (rc, -tw), (rc, -w), (rr, -w), (rr, w), (rc + ta, w), (rc + ta, w + arm),
               (rc, w + arm), (rc, w), (rc, tw), (rb, tw)]
    points = [occ.addPoint(r, 0.0, z) for r, z in corners]
    lines = [occ.addLine(points[i], points[(i + 1) % len(points)]) for i in range(len(points))]
    return occ.addPlaneSurface([occ.addCurveLoop(lines)])


def _blade(occ, g):
    root = g["rim_radius"] - 0.002  # reaches into the rim: the fragment makes one conforming interface
    box = occ.addBox(root, -g["blade_thickness"] / 2, -g["chord"] / 2, g["tip_radius"] - root,
                     g["blade_thickness"], g["chord"])
    occ.rotate([(3, box)], 0, 0, 0, 1, 0, 0, math.radians(g["stagger_deg"]))
    return box


def _classify(gmsh, g, alpha):
    """Physical groups: the cyclic faces, the bore, the groove, the blade volume, the forcing point."""
    model = gmsh.model
    low, high, bore, groove = [], [], [], []
    for _, s in model.getEntities(2):
        x, y, _ = model.occ.getCenterOfMass(2, s)
        theta, lo = math.atan2(y, x), model.getBoundingBox(2, s)[2]
        if abs(theta + alpha / 2) < 1e-9:
            low.append(s)
        elif abs(theta - alpha / 2) < 1e-9:
            high.append(s)
        elif model.getType(2, s) == "Cylinder" and abs(_radius(model, s) - g["bore_radius"]) < 1e-9:
            bore.append(s)
        elif model.getType(2, s) == "Cylinder" and abs(_radius(model, s) - g["contact_radius"]) < 1e-9 \
                and lo > g["rim_width"] / 2 - 1e-6:   # the arm's underside (bounding boxes are padded)
            groove.append(s)
    return low, high, bore, groove


def _radius(model, s) -> float:
    """Distance from the axis of the surface's parametric centre."""
    (u0, v0), (u1, v1) = model.getParametrizationBounds(2, s)
    x, y, _ = model.getValue(2, s, [(u0 + u1) / 2, (v0 + v1) / 2])
    return math.hypot(x, y)


def _tip_point(model, g) -> int:
    """The blade tip's leading-edge corner on the suction side (the forcing / response point)."""
    best, tag = None, -1
    for _, p in model.getEntities(0):
        x, y, z = model.getValue(0, p, [])
        score = abs(math.hypot(x, y) - g["tip_radius"]) * 1e3 + z
        if best is None or score < best:
            best, tag = score, p
    return tag


def write_example(folder, size: float = 0.008, geometry: dict | None = None) -> dict[str, Path]:
    """Mesh the example sector and write ``blisk.msh`` and ``blisk.inp`` into ``folder``."""
    import gmsh

    g = {**EXAMPLE, **(geometry or {})}
    alpha = 2 * math.pi / g["n_sectors"]
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    gmsh.initialize(["-noenv"])
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add("example_blisk")
        occ = gmsh.model.occ
        disk = occ.revolve([(2, _profile(occ, g))], 0, 0, 0, 0, 0, 1, alpha)
        occ.rotate([d for d in disk if d[0] == 3], 0, 0, 0, 0, 0, 1, -alpha / 2)
        volumes, _ = occ.fragment([d for d in disk if d[0] == 3], [(3, _blade(occ, g))])
        occ.synchronize()
        low, high, bore, groove = _classify(gmsh, g, alpha)
        rot = [math.cos(alpha), -math.sin(alpha), 0, 0, math.sin(alpha), math.cos(alpha), 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]
        gmsh.model.mesh.setPeriodic(2, high, low, rot)
        blade = [v for _, v in volumes if math.hypot(*gmsh.model.occ.getCenterOfMass(3, v)[:2]) > g["rim_radius"]]
        gmsh.model.addPhysicalGroup(3, [v for _, v in volumes], name="SECTOR")
        gmsh.model.addPhysicalGroup(3, blade, name=SETS["blade"])
        for name, tags in ((SETS["cyclic_low"], low), (SETS["cyclic_high"], high), (SETS["fixed"], bore),
                           (SETS["groove"], groove)):
            gmsh.model.addPhysicalGroup(2, tags, name=name)
        gmsh.model.addPhysicalGroup(0, [_tip_point(gmsh.model, g)], name=SETS["forcing"])
        for key, value in (("Mesh.MeshSizeMax", size), ("Mesh.ElementOrder", 2), ("Mesh.SecondOrderLinear", 1),
                           ("Mesh.MshFileVersion", 4.1), ("Mesh.Binary", 0), ("Mesh.SaveGroupsOfNodes", 1)):
            gmsh.option.setNumber(key, value)
        gmsh.model.mesh.generate(3)
        out = {"msh": folder / "blisk.msh", "inp": folder / "blisk.inp"}
        for path in out.values():
            gmsh.write(str(path))
    finally:
        gmsh.finalize()
    return out


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("folder")
    parser.add_argument("--size", type=float, default=0.008, help="largest element size (m)")
    args = parser.parse_args(argv)
    for path in write_example(args.folder, args.size).values():
        print(path)


if __name__ == "__main__":
    main()
