"""Cyclic symmetry of the sector (Mead's phase constraint; e.g. Thomas 1979, Petrov 2004).

Sector j occupies theta in [-pi/N + j a, pi/N + j a], a = 2 pi / N. For a nodal diameter k (inter-
sector phase sigma = 2 pi k / N) the field of sector j+1 is the field of sector j rotated by a and
multiplied by e^{i sigma}, so on the right cut u_R = e^{i sigma} R_z(a) u_L. The independent DoFs are
all DoFs but the right cut and the clamped ones; u = T(sigma) q and the sector matrices of ND k are
K_k = T^H K T, M_k = T^H M T (complex Hermitian; real for sigma = 0 and pi).

Two phases, two names. ``nodal_diameter_phase(k, N)`` = 2 pi k / N is the phase of a standing nodal
diameter k (the modal analysis). ``interblade_phase(h, N, EO)`` is the travelling-wave convention
of the reduction and the nonlinear stage: harmonic h of sector j equals harmonic h of the reference
sector times e^{i sigma_h j}, sigma_h = -2 pi h EO / N wrapped to (-pi, pi], i.e. the sector fields
obey u_{j+1} = e^{i sigma_h} u_j (Mead's constraint with that phase). Harmonic h lives in nodal
diameter ``nodal_diameter(h, N, EO)`` = h EO mod N folded to 0..N/2; h = 0 is ND 0 (real). For the
same ND the two phases are complex conjugates (opposite signs), i.e. the same standing mode pair.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp


def nodal_diameter_phase(nd: int, n_sectors: int) -> float:
    """sigma = 2 pi k / N for nodal diameter k."""
    return 2.0 * np.pi * nd / n_sectors


def interblade_phase(h: int, n_sectors: int, engine_order: int) -> float:
    """sigma_h = -2 pi h EO / N wrapped to (-pi, pi]: harmonic h of an engine-order excitation."""
    s = -2.0 * np.pi * ((h * engine_order) % n_sectors) / n_sectors
    return float(s + 2.0 * np.pi if s <= -np.pi else s)


def nodal_diameter(h: int, n_sectors: int, engine_order: int) -> int:
    """Nodal diameter of harmonic h: min(k, N - k) with k = h EO mod N."""
    k = (h * engine_order) % n_sectors
    return int(min(k, n_sectors - k))


def cyclic_transform(n_dofs: int, left_nodes, right_nodes, fixed_dofs, sector_angle: float,
                     sigma: float) -> tuple[sp.csr_matrix, np.ndarray]:
    """T (n_dofs x n_independent) and the independent DoF indices for phase ``sigma``.

    Real when sigma is 0 or pi (standing ND 0 / ND N/2), complex otherwise.
    """
    left_nodes, right_nodes = np.asarray(left_nodes), np.asarray(right_nodes)
    dependent = np.zeros(n_dofs, dtype=bool)
    dependent[(3 * right_nodes[:, None] + np.arange(3)).ravel()] = True
    dependent[np.asarray(fixed_dofs, dtype=int)] = True
    independent = np.flatnonzero(~dependent)
    column = np.full(n_dofs, -1)
    column[independent] = np.arange(len(independent))

    phase = np.exp(1j * sigma)
    real = abs(phase.imag) < 1e-14
    dtype = float if real else complex
    phase = phase.real if real else phase
    c, s = np.cos(sector_angle), np.sin(sector_angle)
    rot = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])

    rows = [independent]
    cols = [np.arange(len(independent))]
    vals = [np.ones(len(independent), dtype=dtype)]
    for a in range(3):
        for b in range(3):
            if rot[a, b] == 0.0:
                continue
            r_dof = 3 * right_nodes + a
            l_col = column[3 * left_nodes + b]
            ok = (l_col >= 0) & ~np.isin(r_dof, fixed_dofs)
            rows.append(r_dof[ok])
            cols.append(l_col[ok])
            vals.append(np.full(ok.sum(), phase * rot[a, b], dtype=dtype))
    T = sp.coo_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                      shape=(n_dofs, len(independent)))
    return T.tocsr(), independent


def project(T: sp.spmatrix, A: sp.spmatrix) -> sp.csr_matrix:
    """T^H A T."""
    return (T.conj().T @ A @ T).tocsr()
