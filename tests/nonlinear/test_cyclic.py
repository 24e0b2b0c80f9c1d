"""Cyclic travelling-wave check (docs/design.md §3.3–3.4, §7): the reference-sector solution
(6 sectors, EO 2, H = 5, a free ring held by friction), shifted in time by EO·j/N of a period for
sector j, satisfies the full 360° harmonic balance — with the contact forces of every sector
recomputed from its own relative displacements — to 1e-10."""
import numpy as np

from ringdamper.fem.cyclic import interblade_phase, nodal_diameter
from ringdamper.nonlinear.contact.friction import contact_aft, dissipated_energy
from ringdamper.nonlinear.fourier import Fourier, to_complex, to_real
from ringdamper.nonlinear.harmonic_balance.epmc import epmc
from ringdamper.status import Status

from .systems import assemble_full, cyclic_structure

N_SECTORS, EO, H = 6, 2, 5


def test_nodal_diameters_and_phases():
    assert [nodal_diameter(h, 30, 27) for h in range(6)] == [0, 3, 6, 9, 12, 15]
    assert np.isclose(interblade_phase(1, 30, 27), -2 * np.pi * 27 / 30 + 2 * np.pi)
    assert interblade_phase(0, 30, 27) == 0.0


def test_sector_solution_satisfies_full_annulus():
    st, contacts, (M0, M1, K0, K1, B) = cyclic_structure(N_SECTORS, EO, H)
    nt = 60                                     # divisible by N / gcd(N, EO) = 3
    alpha = np.geomspace(1e-4, 3e-2, 8)
    bb = epmc(st, contacts, alpha, H=H, nt=nt, mode=0, tol=1e-12)
    assert np.all(bb.status == Status.CONVERGED)
    i = alpha.size - 1
    m = bb.model
    d_last = bb.d[i].reshape(m.C, m.npairs, 3).transpose(1, 2, 0)
    assert dissipated_energy(d_last, bb.lam[i].reshape(m.C, m.npairs, 3).transpose(1, 2, 0))[0] > 0
    omega, xi = bb.omega[i], bb.xi[i]
    Q = np.array([st.modal(h).Phi @ bb.eta[h][i] for h in range(H + 1)])     # (H+1, n)
    f = Fourier(H, nt)
    q0 = f.synth(to_real(Q).T)                                                # (n, nt)
    n = q0.shape[0]
    Mf, Kf = assemble_full(N_SECTORS, M0, M1, K0, K1)
    q = np.concatenate([np.roll(q0, nt * EO * j // N_SECTORS, axis=1) for j in range(N_SECTORS)])
    Qf = to_complex(f.analyse(q).T, H)                                        # (H+1, N n)
    # the shift reproduces the cyclic relation Q_{j,h} = Q_{0,h} e^{i j σ_h}
    for h in range(H + 1):
        sig = interblade_phase(h, N_SECTORS, EO)
        assert np.allclose(Qf[h, n:2 * n], Q[h] * np.exp(1j * sig), atol=1e-12 * np.abs(Q).max())
    force = np.zeros_like(Qf)
    static = contacts.static_force()[0]
    for j in range(N_SECTORS):
        dj = B @ q[j * n:(j + 1) * n]                                         # (3, nt)
        lam = contact_aft(contacts, f, f.analyse(dj)[None], jacobian=False).lam[0]
        lam[:, 0] -= static
        force[:, j * n:(j + 1) * n] = to_complex(lam.T, H) @ B
    h = np.arange(H + 1)[:, None]
    lin = Qf @ Kf.T - (h * omega) ** 2 * (Qf @ Mf.T) - 1j * h * omega * xi * (Qf @ Mf.T)
    residual = lin + force
    scale = np.max(np.abs(Qf @ Kf.T))
    assert np.max(np.abs(residual)) <= 1e-10 * scale
