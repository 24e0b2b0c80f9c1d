"""The vectorised element kernels equal scikit-fem's generic forms (the oracle) to round-off."""
import numpy as np
import pytest
from skfem import Basis, BilinearForm, ElementHex1, ElementHex2, ElementVector, LinearForm, MeshHex1, asm
from skfem.models.elasticity import lame_parameters, linear_elasticity

from ringdamper.fem.elasticity import centrifugal_load, mass_matrix, tangent_stiffness

RHO, OMEGA, E, NU = 4430.0, 200.0, 115e9, 0.33


@pytest.fixture(params=[(ElementHex1, 3), (ElementHex2, 5)], ids=["hex8", "hex27"])
def bases(request):
    element, intorder = request.param
    mesh = MeshHex1.init_tensor(np.linspace(0, 1, 3), np.linspace(0, 1, 2), np.linspace(0, 2, 3))
    mesh = mesh.translated([0.3, 0.1, 0.0])
    return Basis(mesh, element(), intorder=intorder), Basis(mesh, ElementVector(element()), intorder=intorder)


def _rel(a, b):
    return abs(a - b).max() / abs(b).max()


def test_linear_stiffness(bases):
    scalar, vector = bases
    assert _rel(tangent_stiffness(scalar, E, NU), asm(linear_elasticity(*lame_parameters(E, NU)), vector)) < 1e-13


def test_mass_and_spin_softening(bases):
    scalar, vector = bases
    full = asm(BilinearForm(lambda u, v, w: RHO * (u[0] * v[0] + u[1] * v[1] + u[2] * v[2])), vector)
    inplane = asm(BilinearForm(lambda u, v, w: RHO * (u[0] * v[0] + u[1] * v[1])), vector)
    assert _rel(mass_matrix(scalar, RHO), full) < 1e-13
    assert _rel(mass_matrix(scalar, RHO, components=(0, 1)), inplane) < 1e-13


def test_centrifugal_load(bases):
    scalar, vector = bases
    ref = asm(LinearForm(lambda v, w: RHO * OMEGA**2 * (w.x[0] * v[0] + w.x[1] * v[1])), vector)
    assert _rel(centrifugal_load(scalar, RHO, OMEGA), ref) < 1e-13
