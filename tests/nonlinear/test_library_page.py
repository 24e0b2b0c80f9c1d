"""The code of docs/library.md runs as printed (its blocks in order, one namespace), and what it
computes holds: every backbone point converges, the forced response's peak is the E-EBM resonance it
was forced at (0.5 %: the E-EBM's phase-resonance approximation at ζ ≈ 1 %, measured 0.05 %), the
gross-slip end of the backbone tends to the first mode of the structure without the contact (``m2``
slides freely); on the chain of elements only the Jenkins element dissipates (the conservative ones
within 1 % of it at the top point: the AFT's kink error, measured 0.2 %); the dashpot backbone
measured on DoF 1 is stuck at its first point, where it solves the EPMC eigenproblem of the stuck
system with the dashpot."""
import re
from functools import lru_cache
from pathlib import Path

import numpy as np
from scipy.optimize import fsolve

from ringdamper.status import Status

DOC = Path(__file__).resolve().parents[2] / "docs" / "library.md"


@lru_cache(maxsize=1)
def _page() -> dict:
    """The names the page's code blocks define, run in order."""
    names = {"__name__": "library_page"}
    for code in re.findall(r"```python\n(.*?)```", DOC.read_text(), re.S):
        exec(compile(code, str(DOC), "exec"), names)
    return names


def test_library_page_runs_and_its_results_hold():
    names = _page()
    backbone, resonance, curve = names["backbone"], names["resonance"], names["curve"]
    assert np.all(backbone.status == Status.CONVERGED)
    assert curve.status == Status.CONVERGED
    assert abs(np.max(curve.q_h1) / resonance.q_res_h1[12] - 1) <= 5e-3
    M, K = names["M"], names["K"]
    free = np.sqrt(np.min(np.linalg.eigvals(np.linalg.solve(M, K)).real))
    assert abs(backbone.omega[-1] / free - 1) <= 2e-3


def test_library_page_dashpot_backbone_on_dof_1():
    """Measured on DoF 1 (its first harmonic equals the grid, 1e-7); its stuck points solve the EPMC of
    the stuck system with the dashpot, ``det(K_stuck − ω²M + iω(C − ξM)) = 0`` (1e-9 on ω, Newton's
    1e-8·ω on ξ)."""
    names = _page()
    bb, M, C = names["on_dof1"], names["M"], names["dashpot"].harmonics[1].C
    assert np.all(bb.status == Status.CONVERGED)
    np.testing.assert_allclose([abs(bb.harmonics(i)[1][0]) for i in range(bb.alpha.size)], bb.alpha, rtol=1e-7)
    B, k = names["B"], names["contacts"].stuck_stiffness().ravel()
    stuck = names["K"] + B.T @ (k[:, None] * B)

    def det(x):
        d = np.linalg.det(stuck - x[0] ** 2 * M + 1j * x[0] * (C - x[1] * M))
        return [d.real, d.imag]
    w, xi = fsolve(det, [bb.omega[0], bb.xi[0]], xtol=1e-12)
    assert abs(bb.omega[0] / w - 1) <= 1e-9 and abs(bb.xi[0] - xi) <= 1e-8 * w


def test_library_page_chain_dissipates_in_its_friction_element_only():
    names = _page()
    backbone, elements = names["chain_backbone"], names["elements"]
    assert np.all(backbone.status == Status.CONVERGED)
    C, n = backbone.model.C, elements.npairs
    d = backbone.d[-1].reshape(C, n, 3).transpose(1, 2, 0)
    lam = backbone.lam[-1].reshape(C, n, 3).transpose(1, 2, 0)
    energy = elements.energy(d, lam)
    assert energy[2] > 0
    assert np.max(np.abs(energy[[0, 1, 3]])) <= 1e-2 * energy[2]
