"""Modal damping through the EPMC: a friction-damped 2-DoF chain with and without 2 % modal damping
(run by tests/nonlinear/test_examples.py).

    ground –k1– m1 –k2– m2, a preloaded friction contact between m2 and the ground
    (kt = 1e3 N/m, μ N0 = 5 N), modal damping ratios 2 % on both modes of (K, M).

The EPMC puts its negative damping on the mass matrix (Krack's definition), so the backbone's ζ is
the total ratio: at small amplitude the stuck system's (its complex eigenvalue: the contact spring
makes the modal damping non-proportional there), and friction adds its share where the contact
slips.

    python docs/examples/modal_damping_epmc.py [output folder]   # prints ζ, writes modal_damping_epmc.png
"""
import sys
from pathlib import Path

import numpy as np

from ringdamper.nonlinear.contact.friction import FrictionContacts
from ringdamper.nonlinear.harmonic_balance.epmc import epmc
from ringdamper.nonlinear.harmonic_balance.structure import Structure

M = np.diag([1.0, 0.5])
K = np.array([[4.0e4, -1.0e4], [-1.0e4, 1.0e4]])
B = np.array([[0.0, 0.0], [0.0, 1.0], [0.0, 0.0]])           # contact: tangential t1 = x2
CONTACT = FrictionContacts(kn=1e6, kt=1e3, mu=0.25, N0=20.0, gap=0.0)
ZETA = 0.02
ALPHA = np.geomspace(1e-3, 1.0, 25)                            # modal amplitude, kg^0.5 m


def backbones() -> dict:
    """The backbone with the modal damping and without it: ``{"damped": Backbone, "undamped": …}``."""
    e = np.array([1.0, 0.0])
    out = {}
    for name, zeta in (("damped", ZETA), ("undamped", None)):
        structure = Structure.real(M, K, B, e, e, H=3, zeta=zeta)
        out[name] = epmc(structure, CONTACT, ALPHA, H=3)
    return out


def main(folder: Path = Path(".")) -> dict:
    import matplotlib.pyplot as plt

    from ringdamper.plots import save_figure  # Agg backend

    out = backbones()
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(6, 6), sharex=True)
    for name, bb in out.items():
        print(f"{name}: ζ from {bb.zeta[0]:.4f} to a maximum {np.max(bb.zeta):.4f}, f from "
              f"{bb.omega[0] / (2 * np.pi):.3f} to {bb.omega[-1] / (2 * np.pi):.3f} Hz")
        top.semilogx(bb.alpha, bb.omega / (2 * np.pi), label=name)
        bottom.semilogx(bb.alpha, bb.zeta, label=name)
    top.set_ylabel("frequency [Hz]")
    bottom.set_ylabel("damping ratio ζ")
    bottom.set_xlabel("modal amplitude α [kg^0.5 m]")
    top.legend()
    top.set_title("EPMC with 2 % modal damping and friction")
    save_figure(fig, folder / "modal_damping_epmc.png", dpi=120)
    return out


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path("."))
