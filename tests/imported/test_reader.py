"""Node orderings: every supported element type, read from Gmsh's own .msh and from Gmsh's Abaqus export,
reproduces a quadratic map of a box exactly (volume, first moment, mass) and passes the patch test."""
import gmsh
import numpy as np
import pytest
from skfem import Functional

from ringdamper.fem.elasticity import lame, mass_matrix, tangent_stiffness
from ringdamper.imported.checks import element_kind
from ringdamper.imported.mesh import build_mesh
from ringdamper.imported.reader import read_mesh

A, B, C = 0.3, 0.2, 0.1                 # the box (m)
a, b, c = 0.7, 0.4, -0.9                # x -> (x, y + a x^2, z + b x^2 + c y^2): det = 1


def _box(path, hexes: bool, serendipity: bool):
    gmsh.initialize(["-noenv"])
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        v = gmsh.model.occ.addBox(0, 0, 0, A, B, C)
        gmsh.model.occ.synchronize()
        if hexes:
            for _, tag in gmsh.model.getEntities(1):
                gmsh.model.mesh.setTransfiniteCurve(tag, 3)
            for _, tag in gmsh.model.getEntities(2):
                gmsh.model.mesh.setTransfiniteSurface(tag)
                gmsh.model.mesh.setRecombine(2, tag)
            gmsh.model.mesh.setTransfiniteVolume(v)
        else:
            gmsh.option.setNumber("Mesh.MeshSizeMax", 0.1)
        gmsh.model.addPhysicalGroup(3, [v], name="SOLID")
        gmsh.option.setNumber("Mesh.SecondOrderIncomplete", int(serendipity))
        gmsh.option.setNumber("Mesh.ElementOrder", 2)
        gmsh.option.setNumber("Mesh.SaveGroupsOfNodes", 1)
        gmsh.model.mesh.generate(3)
        for suffix in (".msh", ".inp"):
            gmsh.write(str(path.with_suffix(suffix)))
    finally:
        gmsh.finalize()


@pytest.fixture(scope="module")
def boxes(tmp_path_factory):
    folder = tmp_path_factory.mktemp("boxes")
    for name, hexes, serendipity in (("tet10", False, False), ("hex27", True, False), ("hex20", True, True)):
        _box(folder / name, hexes, serendipity)
    return folder


CASES = [("tet10.msh", "tetrahedron10"), ("tet10.inp", "C3D10"), ("hex27.msh", "hexahedron27"),
         ("hex27.inp", "C3D27"), ("hex20.msh", "hexahedron20"), ("hex20.inp", "C3D20")]


def _mapped(boxes, name):
    raw = read_mesh(boxes / name)
    kind = element_kind(raw, allow_linear=False)
    x = raw.coordinates.copy()
    raw.coordinates = np.column_stack([x[:, 0], x[:, 1] + a * x[:, 0] ** 2,
                                       x[:, 2] + b * x[:, 0] ** 2 + c * x[:, 1] ** 2])
    return build_mesh(raw, kind, 1.0, [0.0, 0.0, 1.0]), kind


@pytest.mark.parametrize("name, kind", CASES)
def test_a_quadratic_map_of_a_box_is_exact(boxes, name, kind):
    mesh, k = _mapped(boxes, name)
    assert k.name == kind
    volume = Functional(lambda w: 1.0 + 0.0 * w.x[0]).assemble(mesh.basis)
    moment = Functional(lambda w: w.x[2]).assemble(mesh.basis)
    exact_moment = A * B * C**2 / 2 + b * A**3 / 3 * B * C + c * B**3 / 3 * A * C
    M = mass_matrix(mesh.basis, 4430.0)
    one = np.zeros(M.shape[0])
    one[2::3] = 1.0
    assert volume == pytest.approx(A * B * C, rel=1e-13)
    assert moment == pytest.approx(exact_moment, rel=1e-13)
    assert one @ M @ one == pytest.approx(4430.0 * A * B * C, rel=1e-13)


@pytest.mark.parametrize("name, kind", CASES)
def test_patch_test_linear_field_energy_is_exact(boxes, name, kind):
    """u = G x (G constant): the FE strain energy u^T K u / 2 equals V eps : C eps / 2 exactly."""
    mesh, _ = _mapped(boxes, name)
    E, nu = 115e9, 0.33
    G = np.array([[1.0, 0.3, -0.2], [0.1, -0.5, 0.4], [0.2, 0.6, 0.8]]) * 1e-3
    u = (mesh.nodes @ G.T).ravel()
    K = tangent_stiffness(mesh.basis, E, nu)
    eps = (G + G.T) / 2
    lam, mu = lame(E, nu)
    exact = A * B * C * (lam * np.trace(eps) ** 2 / 2 + mu * np.sum(eps * eps))
    assert 0.5 * u @ K @ u == pytest.approx(exact, rel=1e-11)
