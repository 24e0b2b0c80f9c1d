"""An imported blisk sector as a model the FE and modal functions take (``fem.prestress``,
``modal.analysis.cyclic_modes``): the attributes they read (basis, n_dofs, K, M, material,
n_sectors, sector_angle, fixed_dofs, left_nodes, right_nodes), in SI units with the rotation axis on
Z (``rotation`` takes file directions to model ones).

``load_imported_sector`` reads the file and runs every check of :mod:`.checks` before the
matrices are assembled.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
import scipy.sparse as sp

from ringdamper.fem.elasticity import mass_matrix, tangent_stiffness
from ringdamper.fem.model import CyclicSectorDofs

from . import checks
from .mesh import ImportedMesh, build_mesh
from .reader import read_mesh

LENGTH_UNITS = {"m": 1.0, "mm": 1e-3}


@dataclass
class ImportedSector(CyclicSectorDofs):
    mesh: ImportedMesh
    path: Path
    material: dict
    n_sectors: int
    fixed_nodes: np.ndarray
    left_nodes: np.ndarray       # cyclic_low
    right_nodes: np.ndarray      # cyclic_high, node for node: R(2 pi / N) x_left
    groove_nodes: np.ndarray
    groove_facets: np.ndarray
    forcing_node: int
    forcing_direction: np.ndarray   # unit, model frame
    element_sets: dict              # "blade", "morph" -> element indices (when configured)
    K: sp.csr_matrix
    M: sp.csr_matrix

    @property
    def basis(self):
        return self.mesh.basis

    @property
    def nodes(self) -> np.ndarray:
        return self.mesh.nodes

    @property
    def mass(self) -> float:
        """Sector mass (kg): u^T M u for a unit rigid translation along the axis."""
        one = np.zeros(self.n_dofs)
        one[2::3] = 1.0
        return float(one @ (self.M @ one))


def mesh_path(imported: dict, config_dir) -> Path:
    """``imported.mesh``, relative to the configuration file's folder unless absolute."""
    path = Path(imported["mesh"])
    return path if path.is_absolute() else Path(config_dir) / path


def load_imported_sector(imported: dict, material: dict, config_dir=".", intorder: int | None = None) -> ImportedSector:
    """Read, check and assemble the sector described by the ``imported`` configuration section
    (``intorder``: the quadrature order, by default the exact consistent mass of :mod:`.mesh`)."""
    path = mesh_path(imported, config_dir)
    raw = read_mesh(path)
    kind = checks.element_kind(raw, imported.get("allow_linear_elements", False))
    names = checks.resolve_sets(raw, imported["sets"])
    forcing_label = checks.forcing_node(raw, names["forcing"])
    axis = imported.get("axis", [0.0, 0.0, 1.0])
    checks.length_unit(raw, imported["length_unit"], axis)
    scale = LENGTH_UNITS[imported["length_unit"]]
    mesh = build_mesh(raw, kind, scale, axis, intorder)
    low, high = (mesh.nodes_of_labels(raw.nodes_of(names[k])) for k in ("cyclic_low", "cyclic_high"))
    n = imported["n_sectors"]
    checks.sector_angle(path, mesh.nodes[low], mesh.nodes[high], n, (names["cyclic_low"], names["cyclic_high"]))
    high = checks.cyclic_partners(mesh, low, high, n, checks.smallest_edge(mesh),
                                  (names["cyclic_low"], names["cyclic_high"], path), scale)
    fixed = mesh.nodes_of_labels(raw.nodes_of(names["fixed"]))
    checks.rigid_body(mesh, fixed, low, high, path, names["fixed"])
    groove = mesh.nodes_of_labels(raw.nodes_of(names["groove"]))
    facets = checks.groove_faces(mesh, groove, path, names["groove"])
    direction = mesh.rotation @ np.asarray(imported.get("forcing_direction", [0.0, 0.0, 1.0]), float)
    element_sets = {k: np.flatnonzero(np.isin(mesh.element_label, raw.element_sets[names[k]]))
                    for k in checks.ELEMENT_SETS if k in names}
    E, nu, rho = material["young_modulus"], material["poisson_ratio"], material["density"]
    return ImportedSector(
        mesh=mesh, path=path, material=material, n_sectors=n, fixed_nodes=fixed, left_nodes=low,
        right_nodes=high, groove_nodes=groove, groove_facets=facets,
        forcing_node=int(mesh.nodes_of_labels([forcing_label])[0]),
        forcing_direction=direction / np.linalg.norm(direction), element_sets=element_sets,
        K=tangent_stiffness(mesh.basis, E, nu), M=mass_matrix(mesh.basis, rho))
