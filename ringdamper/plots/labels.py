"""Symbols, units and display scales of the dNNM outputs, shared by the campaign figures."""
from __future__ import annotations

# name -> (symbol, displayed unit, factor from SI to the displayed unit)
OUTPUTS = {
    "q_res_z": (r"$|q_{res,z}|$", "mm", 1e3),
    "omega0": (r"$\omega_0$", "", 1.0),
    "zeta": (r"$\zeta$", "%", 100.0),
    "gamma": (r"$\gamma$", "N", 1.0),
}
# the paper's colours of Figs. 18 and 20
COLOURS = {"omega0": "tab:orange", "zeta": "tab:blue", "gamma": "tab:green"}


def symbol(name: str) -> str:
    return OUTPUTS[name][0]


def label(name: str) -> str:
    """Axis label: symbol and displayed unit."""
    sym, unit, _ = OUTPUTS[name]
    return f"{sym} ({unit})" if unit else sym


def scale(name: str) -> float:
    return OUTPUTS[name][2]
