"""The vectorised element kernels equal scikit-fem's generic forms (the oracle) to round-off."""
import numpy as np
import pytest
from skfem import Basis, BilinearForm, ElementHex1, ElementHex2, ElementVector, LinearForm, MeshHex1, asm
from skfem.models.elasticity import lame_parameters, linear_elasticity

from ringdamper.fem import elasticity
from ringdamper.fem.elasticity import (
    centrifugal_load,
    internal_force,
    mass_matrix,
    small_strain_stress,
    stress_stiffness,
    tangent_stiffness,
)

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


@pytest.mark.parametrize("size", [1, 3])
def test_chunked_assembly_equals_one_chunk(bases, monkeypatch, size):
    """Every operator summed chunk by chunk (1 or 3 of the 4 elements at a time, the last chunk
    shorter) equals the one-chunk sum: the same matrices and vectors to round-off."""
    scalar, _ = bases
    u = 1e-3 * np.random.default_rng(0).standard_normal(3 * scalar.N)

    def operators():
        return [tangent_stiffness(scalar, E, NU), tangent_stiffness(scalar, E, NU, u),
                stress_stiffness(scalar, E, NU, u), mass_matrix(scalar, RHO, components=(0, 1)),
                internal_force(scalar, E, NU, u), centrifugal_load(scalar, RHO, OMEGA),
                small_strain_stress(scalar, E, NU, u)]

    monkeypatch.setattr(elasticity, "CHUNK_ELEMENTS", scalar.nelems)
    whole = operators()
    monkeypatch.setattr(elasticity, "CHUNK_ELEMENTS", size)
    assert len(elasticity.element_chunks(scalar)) == -(-scalar.nelems // size)
    for chunked, ref in zip(operators(), whole):
        assert _rel(chunked, ref) < 1e-14
