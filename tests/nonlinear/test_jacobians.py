"""Analytical Jacobians against central finite differences, to 1e-6 relative: the
contact AFT (both laws) in stick, slip, separation and mixed states, and the full condensed EPMC
and forced residuals (explicit pole modes, rigid-body gauge, complex cyclic matrices); the EPMC's
Jacobian operator's products against its matrix, to round-off."""
import zlib

import numpy as np
import pytest

from ringdamper.nonlinear.contact.friction import FrictionContacts, contact_aft
from ringdamper.nonlinear.fourier import Fourier
from ringdamper.nonlinear.harmonic_balance.condensed import CondensedHBM, pole_modes, structural_damping
from ringdamper.nonlinear.harmonic_balance.epmc import EPMCProblem
from ringdamper.nonlinear.harmonic_balance.forced import ForcedProblem
from ringdamper.nonlinear.solvers.jacobian import bordered, dense, is_operator
from ringdamper.nonlinear.solvers.newton import Factorization

from .systems import cyclic_structure, free_body, multi_dof

STATES = {  # (tangential amplitude / a_s, normal amplitude / (N0/kn))
    "stick": (0.05, 0.1),
    "slip": (6.0, 0.2),
    "separation": (1.5, 3.0),
    "mixed": (1.2, 0.8),
}


def fd_jacobian(fun, x, step):
    cols = []
    for k in range(x.size):
        e = np.zeros(x.size)
        e[k] = step[k]
        cols.append((fun(x + e) - fun(x - e)) / (2 * step[k]))
    return np.array(cols).T


@pytest.mark.parametrize("law", ["jenkins", "coulomb"])
@pytest.mark.parametrize("state", list(STATES))
def test_contact_jacobian(law, state):
    rng = np.random.default_rng(zlib.crc32(f"{law}-{state}".encode()))
    f = Fourier(3, 64)
    kn, kt, mu, N0 = 1e5, 4e4, 0.3, 20.0
    c = FrictionContacts(kn=kn, kt=kt, mu=mu, N0=N0, gap=0.0, law=law)
    ta, na = STATES[state]
    d = rng.standard_normal((1, 3, f.C)) * np.array([na * N0 / kn, ta * mu * N0 / kt,
                                                    ta * mu * N0 / kt])[None, :, None]
    res = contact_aft(c, f, d)
    J = res.jac.reshape(3 * f.C, 3 * f.C)

    def lam(x):
        return contact_aft(c, f, x.reshape(d.shape), jacobian=False).lam.ravel()

    Jfd = fd_jacobian(lam, d.ravel(), np.full(d.size, 1e-6 * np.max(np.abs(d))))
    assert np.max(np.abs(J - Jfd)) <= 1e-6 * np.max(np.abs(Jfd))
    closed = res.normal[0] > 0
    if state == "separation":
        assert (~closed).any()
    if state == "stick":
        blocks = res.jac[0]                                        # (3, C, 3, C)
        for j in (1, 2):
            assert np.allclose(blocks[j, :, j], kt * np.eye(f.C), atol=1e-9 * kt)
        assert np.all(blocks[1:, :, 0] == 0)


def _check_problem(fun, z, scale):
    """The Jacobian against central differences; an operator's product ``J v`` against its matrix
    (to round-off) on random vectors."""
    J = fun(z).J
    A = dense(J)
    Jfd = fd_jacobian(lambda x: fun(x).r, z, 1e-7 * scale)
    err = np.abs(A - Jfd)
    assert np.max(err) <= 1e-6 * np.max(np.abs(Jfd)), np.unravel_index(np.argmax(err), err.shape)
    if is_operator(J):
        V = np.random.default_rng(3).standard_normal((z.size, 4)) * scale[:, None]
        products = np.column_stack([J.matvec(v) for v in V.T])
        assert np.max(np.abs(products - A @ V)) <= 1e-13 * np.max(np.abs(A @ V))


def _state(model, amp, rng):
    y = np.zeros(model.n_core)
    y[:model.n_d] = amp * rng.standard_normal(model.n_d)
    y[model.n_d:] = amp * rng.standard_normal(model.n_core - model.n_d)
    return y


@pytest.mark.parametrize("amp", [2e-5, 3e-4])
def test_epmc_residual_jacobian_multi_dof(amp):
    st, c = multi_dof(H=3)
    w0 = np.sqrt(st.modal(1).w2)
    model = CondensedHBM(st, c, 3, 32, explicit=pole_modes(st, 3, 0.9 * w0[1], 1.1 * w0[1]))
    assert sum(s.size for s in model.S) > 0
    rng = np.random.default_rng(5)
    z = np.r_[_state(model, amp, rng), 1.05 * w0[1], 3.0]
    prob = EPMCProblem(model, phase_index=model.slot_index(1, True, 1))
    _check_problem(lambda x: prob.fun(x, np.log(1e-3)), z, prob.scale(z))


def test_forced_residual_jacobian_cyclic():
    st, c, _ = cyclic_structure(H=3)
    damping = [st.modal(h).damping(0.01) for h in range(4)]
    model = CondensedHBM(st, c, 3, 36, damping=damping, forced=True, gamma=5.0)
    rng = np.random.default_rng(7)
    z = np.r_[_state(model, 4e-4, rng), 90.0]
    prob = ForcedProblem(model)
    _check_problem(lambda x: prob.fun(x), z, prob.scale(z))


def test_bordered_jacobian_is_formed_once_and_factorised_in_place():
    """The forced problem's Jacobian is an operator; bordered twice (ω column, then a hyperplane
    row, as the peak refinement does) it forms the same matrix as stacking the blocks, in Fortran
    order, and an overwriting LU factorises that very array (no copy) to the same solution."""
    st, c, _ = cyclic_structure(H=3)
    damping = [st.modal(h).damping(0.01) for h in range(4)]
    model = CondensedHBM(st, c, 3, 36, damping=damping, forced=True, gamma=5.0)
    rng = np.random.default_rng(8)
    z = np.r_[_state(model, 4e-4, rng), 90.0]
    evaluation = ForcedProblem(model).fun(z)
    J, trivial, n_core, ev = evaluation.J, evaluation.trivial, evaluation.n_core, evaluation.payload
    assert is_operator(J)
    plane = rng.standard_normal(z.size)
    core = model.evaluate(z[:-1], z[-1], 0.0, model.initial_gauge()).J.toarray()
    stacked = np.vstack([np.hstack([core, ev.dr_domega[:, None]]), plane])
    A = dense(bordered(J, rows=plane))
    assert A.flags.f_contiguous and np.array_equal(A, stacked)
    b = rng.standard_normal(z.size)
    copy = Factorization(stacked, trivial, n_core)
    in_place = Factorization(A, trivial, n_core, overwrite=True)
    assert np.array_equal(stacked, np.vstack([np.hstack([core, ev.dr_domega[:, None]]), plane]))
    assert not trivial.any() and np.shares_memory(in_place.lu[0], A)
    assert np.allclose(in_place.solve(b), copy.solve(b), rtol=1e-12, atol=0.0)


@pytest.mark.parametrize("amp", [1e-5, 5e-3])                 # stuck: DC held; slipping: gauge
def test_epmc_residual_jacobian_with_gauge(amp):
    st, c = free_body(H=2)
    model = CondensedHBM(st, c, 2, 32)
    rng = np.random.default_rng(11)
    y = np.zeros(model.n_core)
    d = np.zeros((model.C, model.p))
    d[:, 1] = amp * rng.standard_normal(model.C)
    d[0, 1] *= 0.01
    y[:model.n_d] = d.ravel()
    y[model.n_d:] = amp * rng.standard_normal(model.n_core - model.n_d)
    z = np.r_[y, 150.0, 2.0]
    prob = EPMCProblem(model, phase_index=model.slot_index(1, True, 1))
    ev = model.evaluate(y, 150.0, 2.0, model.initial_gauge())
    assert (ev.drift.size > 0) == (amp > 1e-3)                   # gauge active only in slip
    _check_problem(lambda x: prob.fun(x, np.log(1e-3)), z, prob.scale(z))


@pytest.mark.parametrize("state", ["separation", "mixed", "slip"])
def test_contact_jacobian_restarted_from_own_periodic_state(state):
    """A continuation restarts the march from the periodic slider state of the point itself
    (e.g. a re-solve at an accepted point): the state then equals the bounds it came from
    exactly, and the Jacobian must still follow them (it once took the constant memory)."""
    rng = np.random.default_rng(zlib.crc32(f"restart-{state}".encode()))
    f = Fourier(3, 64)
    kn, kt, mu, N0 = 1e5, 4e4, 0.3, 20.0
    c = FrictionContacts(kn=kn, kt=kt, mu=mu, N0=N0, gap=0.0, law="jenkins")
    ta, na = STATES[state]
    d = rng.standard_normal((1, 3, f.C)) * np.array([na * N0 / kn, ta * mu * N0 / kt,
                                                    ta * mu * N0 / kt])[None, :, None]
    memory = contact_aft(c, f, d, jacobian=False).memory
    res = contact_aft(c, f, d, memory=memory)
    assert np.array_equal(res.memory, memory)                       # periodic state reproduced
    J = res.jac.reshape(3 * f.C, 3 * f.C)

    def lam(x):
        return contact_aft(c, f, x.reshape(d.shape), jacobian=False, memory=memory).lam.ravel()

    Jfd = fd_jacobian(lam, d.ravel(), np.full(d.size, 1e-6 * np.max(np.abs(d))))
    assert np.max(np.abs(J - Jfd)) <= 1e-6 * np.max(np.abs(Jfd))


#: structural damping of the chain: Rayleigh (diagonal in the modes), or with a dashpot on DoF 1 added,
#: which couples the modes (every mode then explicit, the coupling in its rows)
CHAIN_DAMPING = {"modal": np.zeros((3, 3)), "coupled": np.diag([2.0, 0.0, 0.0])}


def _chain_with_every_element(H, dashpots=CHAIN_DAMPING["modal"]):
    """3-DoF chain with a cubic spring, a stop, a Jenkins element and tanh friction (``Elements``),
    damping ``0.01 K + dashpots``."""
    from ringdamper.nonlinear.contact.elements import CubicSpring, Elements, Jenkins, TanhFriction, UnilateralSpring
    from ringdamper.nonlinear.harmonic_balance.structure import Structure

    elements = Elements([CubicSpring([1, 0, 0], 2e3), UnilateralSpring([0, 0, 1], 50.0, 0.01),
                         Jenkins([0, 1, -1], 30.0, 0.5), TanhFriction([1, -1, 0], 0.4, 0.05)], 3)
    K = np.array([[2.0, -1.0, 0.0], [-1.0, 2.0, -1.0], [0.0, -1.0, 2.0]]) * 100.0
    e = np.eye(3)[1]
    return Structure.real(np.eye(3), K, elements.B, e, e, H=H, C=0.01 * K + dashpots), elements


@pytest.mark.parametrize("damping", list(CHAIN_DAMPING))
@pytest.mark.parametrize("amp", [5e-3, 5e-2])
def test_epmc_residual_jacobian_with_every_element_kind(amp, damping):
    """Including the velocity-dependent tanh friction: its ∂Λ/∂ω in the ω column and in the
    amplitude condition's ω derivative; and damping that couples the modes."""
    st, elements = _chain_with_every_element(3, CHAIN_DAMPING[damping])
    model = CondensedHBM(st, elements, 3, 64, damping=structural_damping(st, 3))
    assert (model.coupling[1] is not None) == (damping == "coupled")
    rng = np.random.default_rng(13)
    z = np.r_[_state(model, amp, rng), 12.0, 0.5]
    prob = EPMCProblem(model, phase_index=model.slot_index(1, True, 0))
    _check_problem(lambda x: prob.fun(x, np.log(1e-2)), z, prob.scale(z))


@pytest.mark.parametrize("damping", list(CHAIN_DAMPING))
def test_forced_residual_jacobian_with_every_element_kind(damping):
    st, elements = _chain_with_every_element(3, CHAIN_DAMPING[damping])
    model = CondensedHBM(st, elements, 3, 64, damping=structural_damping(st, 3), forced=True, gamma=2.0)
    rng = np.random.default_rng(17)
    z = np.r_[_state(model, 2e-2, rng), 12.0]
    prob = ForcedProblem(model)
    _check_problem(lambda x: prob.fun(x), z, prob.scale(z))


@pytest.mark.parametrize("system", ["multi_dof", "every_element"])
def test_epmc_residual_jacobian_with_a_dof_amplitude(system):
    """The amplitude condition on ``|w Q_1|`` of a row ``w`` (condensed modes through their
    receptance; tanh friction's ∂Λ/∂ω in its ω derivative)."""
    if system == "multi_dof":
        st, elements = multi_dof(H=3)
        w = np.sqrt(st.modal(1).w2)
        model = CondensedHBM(st, elements, 3, 32, explicit=pole_modes(st, 3, 0.9 * w[1], 1.1 * w[1]))
        omega, phase = 1.05 * w[1], model.slot_index(1, True, 1)
    else:
        st, elements = _chain_with_every_element(3)
        model = CondensedHBM(st, elements, 3, 64, damping=structural_damping(st, 3))
        omega, phase = 12.0, model.slot_index(1, True, 0)
    assert any(Cs.size for Cs in model.Cset)
    row = np.linspace(1.0, -0.5, st.harmonics[1].M.shape[0])
    z = np.r_[_state(model, 3e-3 if system == "every_element" else 2e-5, np.random.default_rng(19)), omega, 0.7]
    prob = EPMCProblem(model, phase_index=phase, amplitude=row)
    _check_problem(lambda x: prob.fun(x, np.log(1e-2)), z, prob.scale(z))
