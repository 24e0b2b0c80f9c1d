"""The import report of a blisk sector: node and element counts, the blisk's mass (sector mass x N)
and the blisk's own cyclic frequencies (no ring) per nodal diameter 0..N/2, at rest and at the
operating speed.

At speed the modal stage's model: the linear centrifugal state of the ND-0 sector, its stress
stiffness and spin softening, K_eff = K + K_sigma(u_s) - Omega^2 M_r (``fem.prestress``), then the
ND-k sector problem K_k phi = w^2 M_k phi (``modal.analysis.cyclic_modes``).
"""

from __future__ import annotations

import hashlib

import scipy.sparse as sp

from ringdamper.fem.prestress import prestressed_stiffness, rpm_to_rad_s
from ringdamper.modal.analysis import cyclic_modes

from .sector import ImportedSector


def file_sha256(path) -> str:
    return hashlib.sha256(open(path, "rb").read()).hexdigest()


def nd_frequencies(sector: ImportedSector, speeds_rpm, n_modes: int, nds=None) -> list[dict]:
    """Rows (nd, mode, speed_rpm, frequency_hz) for ND 0..N/2 (or ``nds``) at each speed."""
    rows = []
    no_contact = sp.csr_matrix((sector.n_dofs, sector.n_dofs))
    for rpm in speeds_rpm:
        K = prestressed_stiffness(sector, rpm_to_rad_s(rpm), no_contact)
        for nd in range(sector.n_sectors // 2 + 1) if nds is None else nds:
            freq = cyclic_modes(sector, K, sector.M, nd, n_modes).frequency
            rows += [{"nd": nd, "mode": j, "speed_rpm": float(rpm), "frequency_hz": float(f)}
                     for j, f in enumerate(freq)]
    return rows


def summary(sector: ImportedSector) -> dict:
    """Counts, mass and the mesh file's identity."""
    mesh = sector.mesh
    return {
        "mesh": str(sector.path), "mesh_sha256": file_sha256(sector.path),
        "element_type": mesh.kind.name, "elements": int(len(mesh.element_label)),
        "nodes": int(len(mesh.nodes)), "dofs": int(sector.n_dofs), "n_sectors": int(sector.n_sectors),
        "sector_mass_kg": sector.mass, "blisk_mass_kg": sector.mass * sector.n_sectors,
        "fixed_nodes": int(len(sector.fixed_nodes)), "cyclic_pairs": int(len(sector.left_nodes)),
        "groove_faces": int(len(sector.groove_facets)),
        "forcing_node_label": int(mesh.node_label[sector.forcing_node]),
    }
