"""The one factorisation entry point (fem.linalg.factorize) on the small model's sector matrices:
every ordering and path gives SuperLU's minimum-degree solutions and modes to round-off, and without
pymetis nested dissection falls back to SuperLU's own ordering, bit for bit."""
import numpy as np
import pytest
import scipy.sparse as sp
from scipy.sparse.linalg import splu

from ringdamper.fem import ordering
from ringdamper.fem.cyclic import cyclic_transform, nodal_diameter_phase, project
from ringdamper.fem.linalg import factorize, lowest_modes
from ringdamper.fem.model import build_model, stuck_contact_stiffness
from ringdamper.geometry.sector import build_sector

SHIFT = -(2 * np.pi * 50.0) ** 2   # below the spectrum: K - SHIFT M is positive definite


@pytest.fixture(scope="module", params=[0, 3], ids=["ND0-real", "ND3-complex"])
def pair(request, small_config):
    """(K_k + K_c, M_k) of the small 27-node model's sector at nodal diameter k."""
    config = {**small_config, "mesh": {**small_config["mesh"], "element_order": 2}}
    model = build_model(build_sector(config, (0.5, -0.2, 0.1)), config)
    T, _ = cyclic_transform(model.n_dofs, model.left_nodes, model.right_nodes, model.fixed_dofs,
                            model.sector_angle, nodal_diameter_phase(request.param, model.n_sectors))
    K = model.K + stuck_contact_stiffness(model, config["contact"])
    return project(T, K), project(T, model.M)


def _reference(A, b):
    """SuperLU with its minimum-degree ordering, as every solve was factorised before."""
    return splu(sp.csc_matrix(A), permc_spec="MMD_AT_PLUS_A", options={"SymmetricMode": True}).solve(b)


def _rel(x, ref):
    return np.abs(x - ref).max() / np.abs(ref).max()


@pytest.mark.parametrize("definite", [False, True])
@pytest.mark.parametrize("name", ordering.ORDERINGS)
def test_solutions_equal_superlu(pair, name, definite):
    K, M = pair
    A = (K - SHIFT * M).tocsc()
    rng = np.random.default_rng(0)
    B = rng.standard_normal((A.shape[0], 6)).astype(A.dtype)
    factors = factorize(A, definite=definite, ordering=name)
    for b in (B[:, 0], B):
        x, ref = factors.solve(b), _reference(A, b)
        assert x.shape == ref.shape
        assert _rel(x, ref) < 1e-9
        assert np.abs(A @ x - b).max() < 1e-9 * np.abs(b).max() * abs(A).max() * np.abs(x).max() / np.abs(b).max()


@pytest.mark.parametrize("name", ordering.ORDERINGS)
def test_modes_equal_superlu(pair, name):
    K, M = pair
    lu = factorize((K - SHIFT * M).tocsc(), definite=True, ordering=name)
    w2, _ = lowest_modes(K, M, 8, SHIFT, lu=lu)
    w2_ref, _ = lowest_modes(K, M, 8, SHIFT)
    assert np.abs(w2 / w2_ref - 1).max() < 1e-8        # Lanczos' convergence level (measured 7e-10)


def test_nested_dissection_is_a_permutation_that_is_used(pair):
    A = pair[0].tocsc()
    factors = factorize(A, ordering="nested_dissection")
    assert factors.ordering == "nested_dissection"
    assert np.array_equal(np.sort(factors.order), np.arange(A.shape[0]))
    assert not np.array_equal(factors.order, np.arange(A.shape[0]))


def test_without_pymetis_nested_dissection_falls_back_to_minimum_degree(pair, monkeypatch):
    real_find_spec = ordering.importlib.util.find_spec
    monkeypatch.setattr(ordering.importlib.util, "find_spec",
                        lambda name, *a: None if name == "pymetis" else real_find_spec(name, *a))
    A = pair[0].tocsc()
    b = np.random.default_rng(1).standard_normal(A.shape[0]).astype(A.dtype)
    factors = factorize(A, ordering="nested_dissection")
    assert factors.ordering == "minimum_degree" and factors.order is None
    assert np.array_equal(factors.solve(b), _reference(A, b))


def test_default_is_minimum_degree_up_to_the_threshold(pair, monkeypatch):
    """Below NESTED_DISSECTION_ROWS the default is SuperLU's own ordering, bit for bit (the 1x and
    2x meshes factorise as before); above it, nested dissection."""
    A = pair[0].tocsc()
    b = np.random.default_rng(2).standard_normal(A.shape[0]).astype(A.dtype)
    assert A.shape[0] <= ordering.NESTED_DISSECTION_ROWS
    assert np.array_equal(factorize(A).solve(b), _reference(A, b))
    monkeypatch.setattr(ordering, "NESTED_DISSECTION_ROWS", A.shape[0] - 1)
    assert factorize(A).ordering == "nested_dissection"


def test_unknown_ordering_is_refused(pair):
    with pytest.raises(ValueError, match="ordering 'amd' is not one of"):
        factorize(pair[0], ordering="amd")
