"""Cyclic symmetry: sector eigenvalues of ND k equal those of the full 360-degree model (docs/design.md §7)."""
import numpy as np
import pytest
from annulus import assemble_full

from ringdamper.fem.cyclic import cyclic_transform, interblade_phase
from ringdamper.fem.linalg import lowest_modes
from ringdamper.fem.model import build_model, stuck_contact_stiffness
from ringdamper.geometry.sector import build_sector
from ringdamper.modal.analysis import cyclic_modes

N_FULL = 60  # lowest modes of the annulus: covers the first two modes of every ND of the coarse mesh


@pytest.fixture(scope="module", params=[1, 2], ids=["hex8", "hex27"])
def annulus(request, small_config):
    config = {**small_config, "mesh": {**small_config["mesh"], "element_order": request.param}}
    model = build_model(build_sector(config, (0.3, -0.5, 0.8)), config)
    K = model.K + stuck_contact_stiffness(model, config["contact"])
    (Kf, Mf), free = assemble_full(model, [K, model.M])
    w2, _ = lowest_modes(Kf[free][:, free], Mf[free][:, free], N_FULL, shift=-1.0)
    return model, K, w2


@pytest.mark.parametrize("nd", [0, 1, 3, 15])
def test_cyclic_eigenvalues_match_full_model(annulus, nd):
    model, K, full = annulus
    cyc = (2 * np.pi * cyclic_modes(model, K, model.M, nd, 2).frequency) ** 2
    for w2 in cyc:
        assert np.min(np.abs(full - w2)) / w2 < 1e-6


def test_nd_1_to_14_are_double_in_the_full_model(annulus):
    model, K, full = annulus
    for nd in range(16):
        cyc = (2 * np.pi * cyclic_modes(model, K, model.M, nd, 2).frequency) ** 2
        for w2 in cyc:
            # 1e-9: the match is ~1e-12, while the flat blade families of neighbouring NDs lie ~1e-7 apart
            multiplicity = int(np.sum(np.abs(full - w2) / w2 < 1e-9))
            assert multiplicity == (1 if nd in (0, 15) else 2), (nd, w2)


def test_travelling_direction_gives_conjugate_matrices(small_config):
    model = build_model(build_sector(small_config, (0.0, 0.0, 0.0)), small_config)
    args = (model.n_dofs, model.left_nodes, model.right_nodes, model.fixed_dofs, model.sector_angle)
    sigma = interblade_phase(1, 30, 27)
    assert sigma == pytest.approx(-2 * np.pi * 27 / 30 + 2 * np.pi)  # ND 3, forward in (-pi, pi]
    Tp, _ = cyclic_transform(*args, sigma)
    Tm, _ = cyclic_transform(*args, -sigma)
    Kp = (Tp.conj().T @ model.K @ Tp).toarray()
    Km = (Tm.conj().T @ model.K @ Tm).toarray()
    assert np.allclose(Kp, Km.conj(), atol=1e-9 * abs(Kp).max())
    assert np.allclose(Kp, Kp.conj().T, atol=1e-9 * abs(Kp).max())  # Hermitian
