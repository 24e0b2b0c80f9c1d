"""Rotating-blisk prestress: centrifugal static state, stress stiffening and spin softening.

At speed Omega the sector (ND 0, contact linearised as springs K_c) is solved linearly,
(K + K_c - Omega^2 M_r) u_s = f_c(Omega), and the vibration stiffness about that state is the linear
prestress one, K_eff(Omega) = K + K_sigma(u_s) + K_c - Omega^2 M_r: K_sigma the geometric (stress)
stiffness of the small-strain stress sigma = C eps(u_s) of that linear solution, -Omega^2 M_r the
spin softening of the centrifugal force's dependence on position. One consistent order: the state is
linear, so its stress is the linear one and no initial-displacement term enters (docs/model.md).
Coriolis terms are neglected, as in the paper (§2.3).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from .cyclic import cyclic_transform, project
from .elasticity import centrifugal_load, mass_matrix, stress_stiffness
from .linalg import solve
from .model import SectorModel


def rpm_to_rad_s(rpm: float) -> float:
    return rpm * 2.0 * np.pi / 60.0


def spin_mass(model: SectorModel) -> sp.csr_matrix:
    """M_r: in-plane (x, y) mass matrix."""
    return mass_matrix(model.basis, model.material["density"], components=(0, 1))


def static_centrifugal(model: SectorModel, omega: float, K_contact: sp.spmatrix) -> np.ndarray:
    """Linear static displacement of the ND-0 sector under the centrifugal load at omega (rad/s)."""
    T, _ = cyclic_transform(model.n_dofs, model.left_nodes, model.right_nodes, model.fixed_dofs,
                            model.sector_angle, 0.0)
    f = centrifugal_load(model.basis, model.material["density"], omega)
    K = model.K + K_contact - omega**2 * spin_mass(model)
    q = solve(project(T, K), T.T @ f)
    return T @ q


def prestressed_stiffness(model: SectorModel, omega: float, K_contact: sp.spmatrix) -> sp.csr_matrix:
    """K_eff(Omega) = K + K_sigma(u_s) + K_c - Omega^2 M_r (equals K + K_c at rest)."""
    if omega == 0.0:
        return (model.K + K_contact).tocsr()
    u_s = static_centrifugal(model, omega, K_contact)
    mat = model.material
    K_s = stress_stiffness(model.basis, mat["young_modulus"], mat["poisson_ratio"], u_s)
    return (model.K + K_s + K_contact - omega**2 * spin_mass(model)).tocsr()
