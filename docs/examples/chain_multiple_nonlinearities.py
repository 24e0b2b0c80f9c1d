"""Chain of three oscillators with five nonlinear elements of three kinds, forced response at H = 7
(run by tests/nonlinear/test_examples.py). The system is NLvib's example 07 (Krack & Gross, *Harmonic
Balance for Nonlinear Vibration Problems*, 2019; EXAMPLES/07_multiDOFoscillator_multipleNonlinearities),
built here from its published definition:

    masses 1, 1, 1 kg; springs 1 N/m ground–m1, m1–m2, m2–m3, m3–ground; dampers 0.02 × each spring
    (C = 0.02 K); force 1 N on m2;
    Jenkins elements (kt = 20 N/m, slip force 1 N) on q1 and on q2 − q1;
    cubic springs (1 N/m³) on q2 and on q3 − q2;
    a unilateral spring (1 N/m, gap 0.25 m) on q3;
    H = 7, 1024 samples per period, excitation 0.5 → 2 rad/s.

    python docs/examples/chain_multiple_nonlinearities.py [output folder]   # writes chain_frf.png
"""
import sys
from pathlib import Path

import numpy as np

from ringdamper.nonlinear.contact.elements import CubicSpring, Elements, Jenkins, UnilateralSpring
from ringdamper.nonlinear.harmonic_balance.frf import forced_response
from ringdamper.nonlinear.harmonic_balance.structure import Structure

K = np.array([[2.0, -1.0, 0.0], [-1.0, 2.0, -1.0], [0.0, -1.0, 2.0]])
M = np.eye(3)
C = 0.02 * K
FORCE = np.array([0.0, 1.0, 0.0])
H, NT = 7, 1024


def system():
    """``(structure, elements)`` of the chain."""
    elements = Elements([Jenkins([1, 0, 0], kt=20.0, slip_force=1.0),
                         Jenkins([-1, 1, 0], kt=20.0, slip_force=1.0),
                         CubicSpring([0, 1, 0], k3=1.0),
                         CubicSpring([0, -1, 1], k3=1.0),
                         UnilateralSpring([0, 0, 1], stiffness=1.0, gap=0.25)], n_dofs=3)
    return Structure.real(M, K, elements.B, FORCE, FORCE, H=H, C=C), elements


def rms(Q: list) -> np.ndarray:
    """Root mean square over a period of every DoF from its harmonics ``Q_h``."""
    return np.sqrt(np.abs(Q[0]) ** 2 + 0.5 * sum(np.abs(q) ** 2 for q in Q[1:]))


def curve():
    """``(forced response, elements)``: 1 N from 0.5 to 2 rad/s."""
    structure, elements = system()
    return forced_response(structure, elements, 1.0, 0.5, 2.0, H=H, nt=NT, stability=False), elements


def main(folder: Path = Path(".")):
    import matplotlib.pyplot as plt

    from ringdamper.plots import save_figure  # Agg backend

    frf, elements = curve()
    amplitudes = np.array([rms(frf.harmonics(j)) for j in range(frf.omega.size)])
    k = np.argmax(amplitudes, axis=0)
    print(f"{frf.omega.size} points; RMS peaks q1, q2, q3: "
          + ", ".join(f"{amplitudes[k[i], i]:.4f} m at {frf.omega[k[i]]:.4f} rad/s" for i in range(3)))
    fig, ax = plt.subplots(figsize=(6, 4))
    for i in range(3):
        ax.plot(frf.omega, amplitudes[:, i], label=f"q{i + 1}")
    ax.set_xlabel("excitation frequency [rad/s]")
    ax.set_ylabel("response amplitude (RMS) [m]")
    ax.set_title("Chain with five nonlinear elements, H = 7")
    ax.legend()
    save_figure(fig, folder / "chain_frf.png", dpi=120)
    return frf, elements, amplitudes


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path("."))
