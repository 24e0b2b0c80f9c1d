"""The reduced sector model: the three steps chained per harmonic, its modes, stuck contact, NetCDF.

``reduce_sector`` runs Craig–Bampton once on the real sector, then for every harmonic h = 0..H
Mead's constraint (ND of sigma_h) and the interface reduction, giving one Hermitian pair (K_h, M_h)
per harmonic in the coordinates y = [p, r, eta] (physical contact + response DoFs, interface modes,
fixed-interface modes). The physical block comes first and is the same in every harmonic, so the
stacked relative contact displacements are d = B_h y (rows pair-major [d_n, d_t1, d_t2],
d = F (u_ring - u_blisk) as ``relative_displacement_operator``): one real B for every harmonic when no
pair reads the right cyclic face (``nodes`` pairs), else B_h folds those weights onto the left
partners with the harmonic's phase (``ContactOperator``).

What the nonlinear stage receives (``reduced_dataset``) is the full modal basis of each (K_h, M_h):
all omega_j^2 and the mass-normalised shapes restricted to B phi_j and to the response (tip Z) DoF.
Since the basis is complete, modal summation over it is exact for the reduced model; in particular
the stuck model of ``modal_stuck_frequencies`` (diag(omega^2) + (B Phi)^H k (B Phi), identity mass)
has exactly the eigenvalues of ``stuck_matrices``.

The mode counts are the ``reduction`` section of the configuration (chosen by the reduction
convergence study, docs/reduction.md); :mod:`ringdamper.reduction.stage` reads them.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import xarray as xr

from ..fem.contact_law import spring_diagonal
from ..fem.cyclic import interblade_phase, nodal_diameter
from ..fem.linalg import eigh_rows
from ..fem.model import SectorModel, node_dofs, relative_displacement_operator
from ..io import variable
from .craig_bampton import CraigBampton, craig_bampton
from .cyclic import mead, rotation_z
from .interface import reduce_interface
from .partition import Partition, partition

DIRECTIONS = ("n", "t1", "t2")


@dataclass
class ReducedHarmonic:
    harmonic: int
    nd: int
    sigma: float
    K: np.ndarray           # Hermitian (real for sigma = 0, pi), order [physical, interface, fixed-interface]
    M: np.ndarray
    n_physical: int
    n_if: int
    n_fi: int
    size_mead: int          # coordinates after Mead's constraint (before the interface reduction)
    B: np.ndarray           # (3m x size): stacked relative contact displacements (ContactOperator.at)

    @property
    def size(self) -> int:
        return self.K.shape[0]


@dataclass
class ReducedSector:
    partition: Partition
    cb: CraigBampton
    harmonics: list[ReducedHarmonic]
    response_index: int           # coordinate of the tip Z DoF
    n_sectors: int
    engine_order: int
    timings: dict = field(default_factory=dict)

    @property
    def dof_counts(self) -> dict:
        h = self.harmonics[0]
        return {"full": len(self.partition.free), "craig_bampton": self.cb.size,
                "mead": h.size_mead, "interface": h.size}


def reduce_sector(model: SectorModel, engine_order: int, n_fi: int, n_if: int,
                  n_harmonics: int | None = None, stiffness: sp.spmatrix | None = None,
                  harmonics=None, keep_modes: bool = False) -> ReducedSector:
    """Craig–Bampton (``n_fi`` fixed-interface modes) + Mead + interface reduction (``n_if``
    interface modes) of ``model`` for harmonics 0..n_harmonics, or the list ``harmonics``.

    ``stiffness`` replaces model.K (e.g. a prestressed stiffness; contact springs must NOT be in
    it: the stuck contact is added on the reduced model).
    """
    if (n_harmonics is None) == (harmonics is None):
        raise ValueError("give exactly one of n_harmonics and harmonics")
    t0 = time.perf_counter()
    K = model.K if stiffness is None else stiffness
    part = partition(model)
    cb = craig_bampton(K, model.M, part.boundary, part.interior, n_fi, keep_modes=keep_modes)
    t1 = time.perf_counter()
    hs = range(n_harmonics + 1) if harmonics is None else harmonics
    rs = reduce_harmonics(model, part, cb, engine_order, hs, n_if)
    rs.timings = {"craig_bampton_s": t1 - t0, "cyclic_interface_s": time.perf_counter() - t1}
    return rs


def reduce_harmonics(model: SectorModel, part: Partition, cb: CraigBampton, engine_order: int,
                     harmonics, n_if: int) -> ReducedSector:
    """Steps 2 and 3 (Mead, interface) of every harmonic on a given CB model."""
    out, contact = [], ContactOperator.of(model, part)
    for h in harmonics:
        sigma = interblade_phase(h, model.n_sectors, engine_order)
        cm = mead(cb, part, model.sector_angle, sigma)
        ir = reduce_interface(cm, n_if)
        out.append(ReducedHarmonic(harmonic=int(h), nd=nodal_diameter(h, model.n_sectors, engine_order),
                                   sigma=sigma, K=ir.K, M=ir.M, n_physical=ir.n_physical,
                                   n_if=n_if, n_fi=cb.n_fi, size_mead=cm.size, B=contact.at(sigma, ir.K.shape[0])))
    return ReducedSector(partition=part, cb=cb, harmonics=out, response_index=contact.response_index,
                         n_sectors=model.n_sectors, engine_order=engine_order)


@dataclass
class ContactOperator:
    """The stacked relative contact displacements G u on the physical DoFs ``part.physical``, built once
    per sector: the block that reads physical DoFs and the block that reads the right cyclic face, folded
    onto the left partners' DoFs through Mead's constraint u_R = e^{i sigma} R_z(2 pi / N) u_L without its
    phase. ``at(sigma, n)`` adds the phase of one harmonic."""
    physical: np.ndarray          # (3m x n_physical) G on part.physical
    folded: np.ndarray | None     # (3m x n_physical) right-face weights on their left partners, or None
    response_index: int           # coordinate of the tip Z DoF

    @classmethod
    def of(cls, model: SectorModel, part: Partition) -> "ContactOperator":
        G = relative_displacement_operator(model).tocsc()
        right = node_dofs(part.right_nodes)
        rest = np.setdiff1d(np.arange(model.n_dofs), np.union1d(part.physical, right))
        if abs(G[:, rest]).sum() != 0:
            raise AssertionError("contact operator touches non-physical DoFs")
        Gr, folded = G[:, right], None
        if Gr.nnz:
            on_left = Gr.toarray().reshape(-1, len(part.right_nodes), 3) @ rotation_z(model.sector_angle)
            read = np.abs(on_left).sum(axis=(0, 2)) > 0
            if not np.all(np.isin(node_dofs(part.left_nodes[read]), part.physical)):
                raise AssertionError("a pair reads a right-face node whose left partner is not physical")
            at = np.searchsorted(part.physical, node_dofs(part.left_nodes)).reshape(-1, 3)
            folded = np.zeros((G.shape[0], len(part.physical)))
            for k in np.flatnonzero(read):
                folded[:, at[k]] += on_left[:, k]
        return cls(physical=G[:, part.physical].toarray(), folded=folded,
                   response_index=int(np.searchsorted(part.physical, model.response_dof())))

    def at(self, sigma: float, n: int) -> np.ndarray:
        """B_h of a reduced model of size ``n`` whose first coordinates are the physical DoFs: complex
        unless sigma is 0 or pi or no pair reads the right face."""
        complex_phase = self.folded is not None and abs(np.sin(sigma)) > 1e-14
        B = np.zeros((self.physical.shape[0], n), dtype=complex if complex_phase else float)
        B[:, :self.physical.shape[1]] = self.physical
        if self.folded is not None:
            B[:, :self.physical.shape[1]] += (np.exp(1j * sigma) if complex_phase else np.cos(sigma)) * self.folded
        return B


# --- stuck contact -------------------------------------------------------------------------------

def stuck_matrices(rh: ReducedHarmonic, kn, kt) -> tuple[np.ndarray, np.ndarray]:
    """(K_h + B_h^H diag(kn, kt, kt) B_h, M_h): the reduced model with stuck contact springs."""
    k = spring_diagonal(kn, kt, rh.B.shape[0] // 3).ravel()
    return rh.K + rh.B.conj().T @ (k[:, None] * rh.B), rh.M


def eigenfrequencies(K: np.ndarray, M: np.ndarray, n_modes: int | None = None) -> np.ndarray:
    """Lowest natural frequencies (Hz) of a Hermitian pair (negative omega^2 give negative Hz)."""
    sub = None if n_modes is None else (0, min(n_modes, K.shape[0]) - 1)
    w2 = sla.eigh(K, M, eigvals_only=True, subset_by_index=sub)
    return np.sign(w2) * np.sqrt(np.abs(w2)) / (2 * np.pi)


def stuck_frequencies(rh: ReducedHarmonic, kn, kt, n_modes: int | None = None):
    return eigenfrequencies(*stuck_matrices(rh, kn, kt), n_modes)


# --- modal basis (what the nonlinear stage receives) ---------------------------------------------

@dataclass
class ModalBasis:
    omega2: np.ndarray      # (n,) rad^2/s^2, ascending
    contact: np.ndarray     # (n, m, 3) complex: B phi_j, pair-major [n, t1, t2]
    response: np.ndarray    # (n,) complex: tip Z component of phi_j


def modal_basis(rh: ReducedHarmonic, response_index: int) -> ModalBasis:
    """All modes of (K_h, M_h), kept at the contact rows B_h and the response coordinate only."""
    B = rh.B
    rows = np.zeros((B.shape[0] + 1, B.shape[1]), dtype=B.dtype)
    rows[:-1] = B
    rows[-1, response_index] = 1.0
    w2, shapes = eigh_rows(rh.K, rh.M, rows)
    m = B.shape[0] // 3
    return ModalBasis(omega2=w2, contact=shapes[:-1].T.reshape(len(w2), m, 3), response=shapes[-1].copy())


def modal_stuck_frequencies(omega2, contact, kn, kt, n_modes: int | None = None) -> np.ndarray:
    """Stuck frequencies (Hz) from the modal data alone: diag(omega^2) + S^H k S, identity mass."""
    omega2 = np.asarray(omega2)
    S = np.asarray(contact).reshape(len(omega2), -1).T          # (3m, n)
    k = spring_diagonal(kn, kt, S.shape[0] // 3).ravel()
    K = np.diag(omega2).astype(S.dtype) + S.conj().T @ (k[:, None] * S)
    return eigenfrequencies(0.5 * (K + K.conj().T), np.eye(len(omega2)), n_modes)


# --- NetCDF ---------------------------------------------------------------------------------------

def reduced_dataset(rs: ReducedSector, kappa, bases: list[ModalBasis] | None = None,
                    attrs: dict | None = None) -> xr.Dataset:
    """The reduced.nc contract (docs/design.md §4): per harmonic, all omega^2 and the mass-normalised mode
    shapes at the contact coordinates and the response DoF (complex split into real/imag)."""
    bases = bases or [modal_basis(rh, rs.response_index) for rh in rs.harmonics]
    hs = rs.harmonics
    m = hs[0].B.shape[0] // 3
    n = hs[0].size
    contact = np.stack([b.contact for b in bases])
    response = np.stack([b.response for b in bases])
    shape_units = "m kg-1/2"
    dims4 = ("harmonic", "mode", "pair", "direction")
    counts = rs.dof_counts
    ds = xr.Dataset(
        {
            "nodal_diameter": variable("harmonic", [rh.nd for rh in hs], "1",
                                       "nodal diameter of the harmonic"),
            "interblade_phase": variable("harmonic", [rh.sigma for rh in hs], "rad",
                                         "inter-sector phase sigma_h, u_{j+1} = exp(i sigma_h) u_j"),
            "omega2": variable(("harmonic", "mode"), np.stack([b.omega2 for b in bases]),
                               "rad2 s-2", "eigenvalue omega^2 of the reduced model (contact free)"),
            "contact_shape_real": variable(dims4, contact.real, shape_units,
                                           "real part of mass-normalised mode shape, relative "
                                           "contact displacement F (u_ring - u_blisk)"),
            "contact_shape_imag": variable(dims4, contact.imag, shape_units,
                                           "imaginary part of mass-normalised mode shape, relative "
                                           "contact displacement F (u_ring - u_blisk)"),
            "response_shape_real": variable(("harmonic", "mode"), response.real, shape_units,
                                            "real part of mass-normalised mode shape, Z at the "
                                            "blade-tip forcing/response node"),
            "response_shape_imag": variable(("harmonic", "mode"), response.imag, shape_units,
                                            "imaginary part of mass-normalised mode shape, Z at the "
                                            "blade-tip forcing/response node"),
        },
        coords={
            "harmonic": variable("harmonic", [rh.harmonic for rh in hs], "1", "harmonic index h"),
            "mode": variable("mode", np.arange(n), "1", "mode index of the reduced model"),
            "pair": variable("pair", np.arange(m), "1", "contact pair index (mesh / static.nc order)"),
            "direction": variable("direction", np.array(DIRECTIONS), "1",
                                  "local contact direction (normal n closing > 0, t1 "
                                  "circumferential, t2 axial)"),
        },
        attrs={
            "kappa": np.asarray(kappa, dtype=float),
            "engine_order": rs.engine_order,
            "n_sectors": rs.n_sectors,
            "n_harmonics": len(hs) - 1,
            "n_fixed_interface_modes": hs[0].n_fi,
            "n_interface_modes": hs[0].n_if,
            "dofs_full": counts["full"],
            "dofs_craig_bampton": counts["craig_bampton"],
            "dofs_mead": counts["mead"],
            "dofs_interface": counts["interface"],
            "n_physical_dofs": hs[0].n_physical,
            "convention": "harmonic h of sector j = harmonic h of the reference sector x "
                          "exp(i j sigma_h); shapes mass-normalised, phi^H M_h phi = 1",
            **(attrs or {}),
        })
    for name in ds.data_vars:   # lossless; the imaginary parts of the real harmonics (ND 0, N/2) vanish
        ds[name].encoding.update(zlib=True, complevel=1, shuffle=True)
    return ds
