"""Duffing oscillator: forced response and its stability (run by tests/nonlinear/test_examples.py).

    m q̈ + c q̇ + k q + k3 q³ = F cos(ω t),    m = 1 kg, k = 1 N/m, c = 0.02 N s/m (ζ = 1 %),
    k3 = 0.5 N/m³, F = 0.05 N,

traced from 0.8 to 1.8 rad/s at H = 1 and H = 5, with Hill's stability at every point. At H = 1 the
amplitude a of every point solves ``((k − m ω² + ¾ k3 a²)² + (c ω)²) a² = F²``; the branch folds
twice and the points between the folds are unstable.

    python docs/examples/duffing_frf.py [output folder]     # prints the peaks, writes duffing_frf.png
"""
import sys
from pathlib import Path

import numpy as np

from ringdamper.nonlinear.contact.elements import CubicSpring, Elements
from ringdamper.nonlinear.harmonic_balance.frf import forced_response
from ringdamper.nonlinear.harmonic_balance.structure import Structure

M, K, C, K3, F = 1.0, 1.0, 0.02, 0.5, 0.05


def curves() -> dict:
    """The forced response at H = 1 and H = 5: ``{H: FRF}``."""
    elements = Elements([CubicSpring([1.0], K3)], n_dofs=1)
    out = {}
    for H in (1, 5):
        duffing = Structure.real(np.array([[M]]), np.array([[K]]), elements.B, np.array([1.0]),
                                 np.array([1.0]), H=H, C=np.array([[C]]))
        out[H] = forced_response(duffing, elements, F, 0.8, 1.8, H=H)
    return out


def main(folder: Path = Path(".")) -> dict:
    import matplotlib.pyplot as plt

    from ringdamper.plots import save_figure  # Agg backend

    out = curves()
    fig, ax = plt.subplots(figsize=(6, 4))
    for H, frf in out.items():
        k = int(np.argmax(frf.q_h1))
        print(f"H = {H}: {frf.omega.size} points, peak {frf.q_h1[k]:.4f} m at {frf.omega[k]:.4f} rad/s, "
              f"{int(np.sum(~frf.stable))} unstable")
        amplitude = np.where(frf.stable, frf.q_h1, np.nan)
        line, = ax.plot(frf.omega, amplitude, label=f"H = {H}, stable")
        ax.plot(frf.omega, np.where(frf.stable, np.nan, frf.q_h1), ":", color=line.get_color(),
                label=f"H = {H}, unstable")
    ax.set_xlabel("excitation frequency ω [rad/s]")
    ax.set_ylabel("first-harmonic amplitude |q₁| [m]")
    ax.set_title("Duffing oscillator, F = 0.05 N")
    ax.legend()
    save_figure(fig, folder / "duffing_frf.png", dpi=120)
    return out


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path("."))
