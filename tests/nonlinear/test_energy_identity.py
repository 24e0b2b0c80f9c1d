"""EPMC energy identity at every converged point of a multi-DoF case (docs/design.md §7):

    ξ π ω Σ_h h² Q_hᴴ M_h Q_h  =  Σ_pairs ∮ λ · ḋ dt   (AFT),

through stick, slip, lift-off of the preloaded pair and closure of the gapped pair (H = 3)."""
import numpy as np

from ringdamper.nonlinear.contact.friction import contact_aft, dissipated_energy
from ringdamper.nonlinear.harmonic_balance.eebm import eebm
from ringdamper.nonlinear.harmonic_balance.epmc import epmc
from ringdamper.status import Status

from .systems import multi_dof


def test_energy_identity_along_backbone():
    st, c = multi_dof(H=3)
    alpha = np.logspace(-4, -1.5, 15)
    bb = epmc(st, c, alpha, H=3, nt=64, mode=1, tol=1e-11)
    assert np.all(bb.status == Status.CONVERGED)
    m = bb.model
    lifted = closed = slipped = False
    for i in range(alpha.size):
        d = bb.d[i].reshape(m.C, m.npairs, 3).transpose(1, 2, 0)
        lam = bb.lam[i].reshape(m.C, m.npairs, 3).transpose(1, 2, 0)
        w_contact = dissipated_energy(d, lam).sum()
        w_modal = bb.xi[i] * np.pi * bb.omega[i] * sum(
            h * h * np.sum(np.abs(bb.eta[h][i]) ** 2) for h in range(1, m.H + 1))
        scale = np.pi * np.max(np.abs(lam[:, :, 1:])) * np.max(np.abs(d[:, :, 1:]))
        assert abs(w_contact - w_modal) <= 1e-9 * scale
        normal = contact_aft(c, m.fourier, d, jacobian=False).normal
        lifted |= bool(np.any(normal[0] == 0))
        closed |= bool(np.any(normal[1] > 0))
        slipped |= w_contact > 1e-6 * scale
    assert lifted and closed and slipped                     # all contact states visited
    res = eebm(bb, zeta_s=0.0)                               # E_damp without ζs = contact energy
    assert np.allclose(res.e_damp, res.energy_dissipated.sum(axis=1), rtol=1e-8,
                       atol=1e-9 * np.max(res.e_damp))
