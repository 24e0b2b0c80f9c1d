"""The harmonics of every DoF are in the results, and any DoF or linear combination of DoFs can be
the response measure (``Structure.with_response``).

Oracles: the EPMC's amplitude condition ``Q_1ᴴ M Q_1 = α²`` on the DoF harmonics of every backbone
point (1e-7: the Newton tolerance is 1e-8, measured 5e-9); the linear forced response's DoF
harmonics against the receptance ``(K − ω²M + iωC)⁻¹ F`` at every point (harmonic 1, 1e-8) and
zero elsewhere; the measures reported for another response row equal that row applied to the DoF
harmonics (1e-12).

The EPMC amplitude on a DoF (``epmc(..., amplitude=w)``): the same backbone as the modal one, only
parametrised by ``|w Q_1|``: continued on the DoF amplitudes the modal backbone has at its points, it
returns those points' ω and ξ (1e-8, Newton's tolerance) and E-EBM forcing, and ``|w Q_1|`` equals
the grid (1e-7), through the stuck points and the slipping ones, for a DoF and a relative
displacement."""
import numpy as np
import pytest

from ringdamper.nonlinear.harmonic_balance.eebm import eebm
from ringdamper.nonlinear.harmonic_balance.epmc import epmc
from ringdamper.nonlinear.harmonic_balance.frf import forced_response
from ringdamper.nonlinear.harmonic_balance.response import time_peak
from ringdamper.nonlinear.harmonic_balance.structure import Structure
from ringdamper.status import Status

from .test_structural_damping import FRICTION, OPEN, B, E, K, M, _natural_frequencies, _structure


def test_backbone_harmonics_satisfy_the_amplitude_condition_and_any_row_is_a_measure():
    alpha = np.geomspace(1e-3, 1.0, 8)
    relative = np.array([1.0, -1.0])                       # x1 − x2
    st = _structure(H=3).with_response(relative)
    bb = epmc(st, FRICTION, alpha, H=3)
    res = eebm(bb, zeta_s=1e-3)
    for i in range(alpha.size):
        Q = bb.harmonics(i)
        assert len(Q) == 4 and Q[0].shape == (2,)
        np.testing.assert_allclose(np.real(np.vdot(Q[1], M @ Q[1])), alpha[i] ** 2, rtol=1e-7)
        q = np.array([relative @ Qh for Qh in Q])
        np.testing.assert_allclose(res.q_res_h1[i], abs(q[1]), rtol=1e-12)
        np.testing.assert_allclose(res.q_res_peak[i], time_peak(q), rtol=1e-12)


@pytest.mark.parametrize("row", [np.array([0.0, 1.0]), np.array([1.0, -1.0])], ids=["dof_2", "x1_minus_x2"])
def test_epmc_on_a_dof_amplitude_is_the_modal_backbone_reparametrised(row):
    modal = epmc(_structure(H=3), FRICTION, np.geomspace(1e-3, 1.0, 10), H=3)
    assert np.all(modal.status == Status.CONVERGED) and np.max(modal.zeta) > 0.01     # slipping points
    dof_alpha = np.array([abs(row @ modal.harmonics(i)[1]) for i in range(modal.alpha.size)])
    on_dof = epmc(_structure(H=3), FRICTION, dof_alpha, H=3, amplitude=row)
    assert np.all(on_dof.status == Status.CONVERGED)
    np.testing.assert_allclose(on_dof.omega, modal.omega, rtol=1e-8)
    assert np.all(np.abs(on_dof.xi - modal.xi) <= 1e-8 * modal.omega)        # Newton: ξ scaled by ω
    np.testing.assert_allclose([abs(row @ on_dof.harmonics(i)[1]) for i in range(dof_alpha.size)],
                               dof_alpha, rtol=1e-7)
    np.testing.assert_allclose(eebm(on_dof, zeta_s=1e-3).gamma, eebm(modal, zeta_s=1e-3).gamma, rtol=1e-6)


def test_an_amplitude_row_of_the_wrong_shape_or_that_the_mode_does_not_move_is_named():
    with pytest.raises(ValueError, match=r"amplitude: expected a row of shape \(2,\)"):
        epmc(_structure(H=1), FRICTION, np.array([1e-3]), H=1, amplitude=np.ones(3))
    free = Structure.real(np.eye(2), np.diag([1e4, 4e4]), B, E, E, H=1)      # mode 1 moves DoF 1 only
    with pytest.raises(ValueError, match="amplitude: the followed mode does not move this row"):
        epmc(free, OPEN, np.array([1e-3]), H=1, amplitude=np.array([0.0, 1.0]))


def test_forced_response_harmonics_of_every_dof_are_the_receptance():
    C = 3.0 * M + 2e-4 * K
    w1 = _natural_frequencies()[0]
    st = _structure(C=C).with_response(np.array([0.0, 1.0]))          # observe DoF 2
    frf = forced_response(st, OPEN, 1.0, 0.9 * w1, 1.1 * w1, H=3, tol=1e-12, stability=False)
    for j, w in enumerate(frf.omega):
        Q = frf.harmonics(j)
        exact = np.linalg.solve(K - w * w * M + 1j * w * C, np.array([1.0, 0.0]))
        np.testing.assert_allclose(Q[1], exact, rtol=1e-8)
        assert max(np.max(np.abs(Q[h])) for h in (0, 2, 3)) <= 1e-10 * np.max(np.abs(exact))
        np.testing.assert_allclose(frf.q_h1[j], abs(Q[1][1]), rtol=1e-12)


def test_a_response_of_the_wrong_shape_is_named():
    with pytest.raises(ValueError, match=r"response: expected shape \(n,\) or \(4, n\), got \(3, 2\)"):
        _structure(H=3).with_response(np.ones((3, 2)))
