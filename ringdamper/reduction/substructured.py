"""One ring on the fixed substructure: the morph zone assembled and coupled to the super-element.

Per ring only the morph zone's elements (the ring and the arm's groove zone) are assembled
(``build_model(..., elements=split.morph_elements)``). In the independent coordinates of the cyclic
transform T(sigma) the coupled model is the morph zone's T^H A T on the coordinates it touches,
plus the super-element (``reduction.superelement``) on its boundary b, plus its modal coordinates:

    K = [[K_Z + K_SE,bb, 0], [0, Lambda]],   M = [[M_Z + M_SE,bb, M_SE,b eta], [., I]].

* static (ND 0): K_Z - Omega^2 M_r,Z + static_K on b, f_Z + static_f on b: the monolithic
  static problem condensed exactly onto the morph zone (N0 and gaps equal to round-off);
* harmonic h: the coupled pair reduced by Craig–Bampton (``hermitian_cb.condense``) onto the
  physical DoFs (contact pairs and tip, the monolithic chain's, in its order), with
  n_interface_modes + n_fixed_interface_modes fixed-interface modes of the rest: the reduced model
  has the monolithic one's size and coordinate layout, so ``reduced_dataset`` writes it unchanged.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ..fem.cyclic import nodal_diameter, project
from ..fem.model import SectorModel, build_model
from ..geometry.sector import build_sector
from ..geometry.split import SectorSplit, split_sector
from .hermitian_cb import condense
from .partition import partition
from .reduced import ContactOperator, ReducedHarmonic
from .superelement import SuperElement, config_hash, coordinates, fixed_positions_hash, sector_transform


class SuperElementMismatch(ValueError):
    """A super-element file that was not built for this configuration or mesh."""


def morph_model(config: dict, kappa, se: SuperElement, source="the super-element") -> tuple[SectorModel, SectorSplit]:
    """The morph zone's model of ring ``kappa``, checked against the super-element ``se``."""
    if se.config_sha256 != config_hash(config):
        raise SuperElementMismatch(f"{source} was built for another blisk configuration (material, "
                                   "mesh, operation, geometry except the ring's thickness and "
                                   "clearance, reduction counts): rebuild it")
    split = split_sector(config)
    model = build_model(build_sector(config, kappa), config, elements=split.morph_elements)
    if fixed_positions_hash(model, split) != se.fixed_positions_sha256:
        raise SuperElementMismatch(f"{source}: the fixed part's nodes of kappa={list(kappa)} are "
                                   "not those it was built on")
    return model, split


def _embed(n: int, at: np.ndarray, block: np.ndarray) -> sp.csr_matrix:
    """The dense ``block`` placed at rows and columns ``at`` of an n x n sparse matrix."""
    rows = np.repeat(at, len(at))
    return sp.csr_matrix((block.ravel(), (rows, np.tile(at, len(at)))), shape=(n, n))


def _positions(se: SuperElement, independent: np.ndarray, keep: np.ndarray) -> np.ndarray:
    """Positions within ``keep`` (independent coordinates) of the super-element's boundary."""
    b = np.searchsorted(independent, se.boundary)
    if not np.array_equal(independent[b], se.boundary):
        raise SuperElementMismatch("the super-element's boundary is not among this sector's DoFs")
    return np.searchsorted(keep, b)


def coupled_static(K_Z: sp.spmatrix, f_Z: np.ndarray, se: SuperElement, model: SectorModel,
                   split: SectorSplit, T: sp.csr_matrix, independent: np.ndarray):
    """(K, f, keep): the ND-0 static problem of the ring on the static super-element, on the
    independent coordinates ``keep`` of the morph zone (the super-element's boundary among them)."""
    keep = coordinates(model, split, T)[2]
    at = _positions(se, independent, keep)
    K = sp.csr_matrix(K_Z)[keep][:, keep] + _embed(len(keep), at, se.static_K)
    f = f_Z[keep].copy()
    f[at] += se.static_f
    return K.tocsr(), f, keep


def coupled_harmonic(model: SectorModel, split: SectorSplit, se: SuperElement, k: int):
    """(K, M, keep) of harmonic ``se.harmonics[k]``: coordinates [keep, modes of the fixed part]."""
    T, independent = sector_transform(model, se.sigma[k])
    keep = coordinates(model, split, T)[2]
    at = _positions(se, independent, keep)
    nk = len(keep)
    n_s = len(se.omega2[k])
    index = np.concatenate([at, nk + np.arange(n_s)])
    n = nk + n_s
    K_Z, M_Z = project(T, model.K)[keep][:, keep], project(T, model.M)[keep][:, keep]
    K = sp.block_diag([K_Z, sp.csr_matrix((n_s, n_s))]) + _embed(n, index, se.K[k])
    M = sp.block_diag([M_Z, sp.csr_matrix((n_s, n_s))]) + _embed(n, index, se.M[k])
    return K.tocsr(), M.tocsr(), keep, independent


def reduce_on_superelement(model: SectorModel, split: SectorSplit, se: SuperElement,
                           engine_order: int, n_fi: int, n_if: int) -> "SubstructuredSector":
    """Every harmonic of ``se`` coupled and reduced onto the physical DoFs (module docstring)."""
    part = partition(model)
    out, sizes, contact = [], {}, ContactOperator.of(model, part)
    for k, h in enumerate(se.harmonics):
        K, M, keep, independent = coupled_harmonic(model, split, se, k)
        p = np.searchsorted(keep, np.searchsorted(independent, part.physical))
        interior = np.setdiff1d(np.arange(K.shape[0]), p)
        cb = condense(K, M, p, interior, n_if + n_fi)
        out.append(ReducedHarmonic(harmonic=int(h), nd=nodal_diameter(int(h), model.n_sectors, engine_order),
                                   sigma=float(se.sigma[k]), K=cb.K, M=cb.M, n_physical=len(p),
                                   n_if=n_if, n_fi=n_fi, size_mead=K.shape[0],
                                   B=contact.at(float(se.sigma[k]), cb.K.shape[0])))
        sizes = {"full": len(part.free), "craig_bampton": K.shape[0], "mead": K.shape[0],
                 "interface": cb.K.shape[0]}
    return SubstructuredSector(harmonics=out, response_index=contact.response_index,
                               n_sectors=model.n_sectors, engine_order=engine_order, dof_counts=sizes)


class SubstructuredSector:
    """What ``reduced_dataset`` reads of a reduced sector, for the substructured chain."""

    def __init__(self, harmonics, response_index, n_sectors, engine_order, dof_counts):
        self.harmonics, self.response_index = harmonics, response_index
        self.n_sectors, self.engine_order, self.dof_counts = n_sectors, engine_order, dof_counts
