"""Two-DoF oscillator with dry friction regularised in velocity: its first nonlinear mode (EPMC),
H = 21 (run by tests/nonlinear/test_examples.py). The system is NLvib's example 05 (Krack & Gross,
*Harmonic Balance for Nonlinear Vibration Problems*, 2019; EXAMPLES/05_twoDOFoscillator_tanhDryFriction_NM,
after Laxalde & Thouverez 2009), built here from its published definition:

    masses 0.02, 1 kg; springs 0 (ground–m1), 40 (m1–m2), 600 N/m (m2–ground); no dampers;
    tanh friction on q1, f = 5 N · tanh(q̇1 / 0.05 m/s); H = 21, 1024 samples per period.

At small amplitude the friction (a damper of 100 N s/m at rest) holds the light mass: the mode is that
of the system with m1 fixed. At large amplitude m1 slides: the mode tends to the free system's. In
between the friction damps the mode most.

    python docs/examples/tanh_friction_nm.py [output folder]   # prints the range, writes tanh_friction_nm.png
"""
import sys
from pathlib import Path

import numpy as np

from ringdamper.nonlinear.contact.elements import Elements, TanhFriction
from ringdamper.nonlinear.harmonic_balance.epmc import epmc
from ringdamper.nonlinear.harmonic_balance.structure import Structure

M = np.diag([0.02, 1.0])
K = np.array([[40.0, -40.0], [-40.0, 640.0]])
H, NT = 21, 1024
ALPHA = np.logspace(-1.5, 1.0, 41)                         # modal amplitude, kg^0.5 m


def system():
    """``(structure, elements)`` of the oscillator (observed at m2)."""
    elements = Elements([TanhFriction([1.0, 0.0], slip_force=5.0, eps=0.05)], n_dofs=2)
    e = np.array([0.0, 1.0])
    return Structure.real(M, K, elements.B, e, e, H=H), elements


def fixed_and_free():
    """First natural frequency [rad/s] with m1 held and with m1 free."""
    free = np.sqrt(np.min(np.linalg.eigvals(np.linalg.solve(M, K)).real))
    return np.sqrt(K[1, 1] / M[1, 1]), free


def mode():
    """``(backbone, elements)``: the first nonlinear mode on ``ALPHA``."""
    structure, elements = system()
    return epmc(structure, elements, ALPHA, H=H, nt=NT), elements


def main(folder: Path = Path(".")):
    import matplotlib.pyplot as plt

    from ringdamper.plots import save_figure  # Agg backend

    backbone, elements = mode()
    fixed, free = fixed_and_free()
    print(f"ω/ω_fixed from {backbone.omega[0] / fixed:.4f} to {backbone.omega[-1] / fixed:.4f} "
          f"(free: {free / fixed:.4f}); largest ζ {100 * np.max(backbone.zeta):.2f} %")
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(6, 6), sharex=True)
    top.semilogx(ALPHA, backbone.omega / fixed)
    top.axhline(free / fixed, ls=":", color="k", label="m1 free")
    top.set_ylabel("ω / ω (m1 held)")
    top.legend()
    bottom.semilogx(ALPHA, 100 * backbone.zeta)
    bottom.set_ylabel("modal damping ratio [%]")
    bottom.set_xlabel("modal amplitude α [kg^0.5 m]")
    top.set_title("Two DoF with tanh friction: first nonlinear mode, H = 21")
    save_figure(fig, folder / "tanh_friction_nm.png", dpi=120)
    return backbone, elements


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path("."))
