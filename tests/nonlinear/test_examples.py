"""The examples of docs/examples/ run, and what they compute holds.

Duffing (``duffing_frf.py``): at H = 1 every point of the forced response solves the closed-form
frequency–amplitude relation ``((k − mω² + ¾ k3 a²)² + (cω)²) a² = F²`` (1e-5 relative: Newton stops
at 1e-8 on the unknowns, and the relation, of degree 6 in a, amplifies that near the folds; measured
1.3e-6); Hill's method finds the points between the two folds unstable and the others
stable (the two points next to each fold, where the exponent crosses zero, are not asserted); H = 5
moves the peak by less than 2 % (measured 0.7 %).

Modal damping through the EPMC (``modal_damping_epmc.py``): at the stuck amplitudes the damped
backbone's ζ is the stuck system's first complex eigenvalue (1e-5 relative, measured 3e-7: the EPMC's
definition and the eigenvalue part as the non-proportional damping grows, docs/library.md) and the
undamped one's is zero (1e-12); in gross slip the structural share of ζ tends to the free mode's 2 %
(1e-4 absolute, measured 6e-7).

Chain with five elements of three kinds (``chain_multiple_nonlinearities.py``, NLvib's example 07
system at H = 7): at every point of the forced response the work of the force over a period equals
the viscous dissipation plus the elements' (1e-4 of the work, measured 5.8e-6: the unilateral
spring's kink in the AFT and the Newton tolerance), the cubic and unilateral springs dissipate
nothing (1e-4) and the Jenkins elements take up to more than 30 % of it.

Tanh friction (``tanh_friction_nm.py``, NLvib's example 05 system at H = 21): at every backbone point
the EPMC's negative damping balances the friction's dissipation, ``ξ ∫ q̇ᵀ M q̇ dt = ∮ f du``: the ξ
that balances them lies within Newton's tolerance on ξ of the computed one (tol·ω, the EPMC's
convergence scale of ξ; measured up to 0.31 of it, 0.46 with chord steps); at the smallest amplitude the mode is that of
the system with m1 held, at the largest that of the free system (1e-3; measured 5e-6 and 2e-6), and the
damping peaks in between (more than 10× either end)."""
import inspect

import numpy as np

from ringdamper.bench.library import load_example as _example
from ringdamper.nonlinear.harmonic_balance.epmc import epmc

EPMC_TOL = inspect.signature(epmc).parameters["tol"].default   # the examples' Newton tolerance


def test_duffing_example(tmp_path):
    duffing = _example("duffing_frf")
    out = duffing.main(tmp_path)
    assert (tmp_path / "duffing_frf.png").stat().st_size > 0
    frf = out[1]
    w, a = frf.omega, frf.q_h1
    relation = ((duffing.K - duffing.M * w ** 2 + 0.75 * duffing.K3 * a ** 2) ** 2 + (duffing.C * w) ** 2) * a ** 2
    np.testing.assert_allclose(relation, duffing.F ** 2, rtol=1e-5)
    turns = np.flatnonzero(np.diff(np.sign(np.diff(w))) != 0) + 1          # the two folds
    assert turns.size == 2
    first, second = turns
    middle = np.arange(first + 2, second - 1)
    outer = np.r_[np.arange(0, first - 1), np.arange(second + 2, w.size)]
    assert middle.size > 3 and not frf.stable[middle].any()
    assert frf.stable[outer].all()
    assert abs(np.max(out[5].q_h1) / np.max(a) - 1) <= 0.02


def test_modal_damping_example(tmp_path):
    example = _example("modal_damping_epmc")
    out = example.main(tmp_path)
    assert (tmp_path / "modal_damping_epmc.png").stat().st_size > 0
    damped, undamped = out["damped"], out["undamped"]
    assert np.all(damped.status == 0) and np.all(undamped.status == 0)
    stuck = example.K + example.B.T @ np.diag(example.CONTACT.stuck_stiffness().ravel()) @ example.B
    C = damped.model.structure.damping_matrix(1).real
    n = stuck.shape[0]
    state = np.block([[np.zeros((n, n)), np.eye(n)],
                      [-np.linalg.solve(example.M, stuck), -np.linalg.solve(example.M, C)]])
    lam = np.linalg.eigvals(state)
    lam = lam[lam.imag > 0]
    first = lam[np.argmin(np.abs(lam))]
    np.testing.assert_allclose(damped.zeta[0], -first.real / abs(first), rtol=1e-5)
    assert abs(undamped.zeta[0]) <= 1e-12
    assert abs(damped.zeta[-1] - undamped.zeta[-1] - example.ZETA) <= 1e-4     # gross slip: the free mode's


def test_chain_example_balances_the_work_of_the_force_at_every_point(tmp_path):
    example = _example("chain_multiple_nonlinearities")
    frf, elements, amplitudes = example.main(tmp_path)
    assert (tmp_path / "chain_frf.png").stat().st_size > 0
    assert frf.status == 0 and amplitudes.shape == (frf.omega.size, 3)
    nt = 4096
    tau = 2 * np.pi * np.arange(nt) / nt
    C = frf.problem.model.C
    friction = 0.0
    for j, omega in enumerate(frf.omega):
        Q = frf.harmonics(j)
        velocity = sum(np.real(1j * h * omega * np.outer(Q[h], np.exp(1j * h * tau))) for h in range(1, example.H + 1))
        force = np.real(np.outer(example.FORCE, np.exp(1j * tau)))
        dt = 2 * np.pi / omega / nt
        work = np.sum(force * velocity) * dt
        viscous = np.sum(velocity * (example.C @ velocity)) * dt
        ev = frf.points[j].payload
        d = ev.d.reshape(C, elements.npairs, 3).transpose(1, 2, 0)
        lam = ev.lam.reshape(C, elements.npairs, 3).transpose(1, 2, 0)
        per_element = elements.energy(d, lam)
        assert abs(work - viscous - per_element.sum()) <= 1e-4 * work
        assert np.max(np.abs(per_element[2:])) <= 1e-4 * work          # cubic and unilateral: conservative
        friction = max(friction, per_element[:2].sum() / work)
    assert friction > 0.3                                                # the Jenkins elements do damp


def test_tanh_friction_example_balances_energy_and_meets_both_limits(tmp_path):
    example = _example("tanh_friction_nm")
    backbone, elements = example.main(tmp_path)
    assert (tmp_path / "tanh_friction_nm.png").stat().st_size > 0
    assert np.all(backbone.status == 0)
    C = backbone.model.C
    for i in range(backbone.alpha.size):
        Q = backbone.harmonics(i)
        kinetic = np.pi * backbone.omega[i] * sum(h * h * np.real(np.vdot(Q[h], example.M @ Q[h]))
                                                  for h in range(1, example.H + 1))
        d = backbone.d[i].reshape(C, elements.npairs, 3).transpose(1, 2, 0)
        lam = backbone.lam[i].reshape(C, elements.npairs, 3).transpose(1, 2, 0)
        dissipated = elements.energy(d, lam).sum()
        # the damping that balances the energies is ξ to within Newton's tolerance on ξ (tol·ω)
        assert abs(backbone.xi[i] - dissipated / kinetic) <= EPMC_TOL * backbone.omega[i]
    fixed, free = example.fixed_and_free()
    assert abs(backbone.omega[0] / fixed - 1) <= 1e-3
    assert abs(backbone.omega[-1] / free - 1) <= 1e-3
    assert np.max(backbone.zeta) > 10 * max(backbone.zeta[0], backbone.zeta[-1])
