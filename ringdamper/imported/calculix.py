"""The independent check of the import report: the same sector mesh (10-node tetrahedra) as a
CalculiX cyclic-symmetry deck, run with ``ccx`` (Debian's calculix-ccx), and its frequencies per
nodal diameter read back from the .dat file.

Deck (CalculiX User's Manual, *CYCLIC SYMMETRY MODEL, *TIE, *FREQUENCY, *SELECT CYCLIC SYMMETRY
MODES): the high face's nodes tied to the low face's (``*TIE, CYCLIC SYMMETRY``, dependent surface
first), the axis through (0, 0, 0) and (0, 0, 1). Prestressed: a *STATIC step with NLGEOM under
``*DLOAD CENTRIF`` (rho Omega^2 r body force about the axis), then a *FREQUENCY step with
PERTURBATION about that state.
"""

from __future__ import annotations

import subprocess
import tempfile
from pathlib import Path

import numpy as np

from .elements import ABAQUS
from .writers import file_connectivity

CCX = "ccx"


def _set_lines(name: str, nodes) -> list[str]:
    labels = [str(n + 1) for n in nodes]
    return [f"*NSET, NSET={name}"] + [", ".join(labels[i:i + 16]) for i in range(0, len(labels), 16)]


def cyclic_deck(sector, n_modes: int, omega: float = 0.0, nlgeom: bool = True) -> str:
    """The deck of ``sector`` (an :class:`~.sector.ImportedSector` of 10-node tets), model frame;
    at ``omega`` > 0 (rad/s) prestressed, the static step geometrically nonlinear or linear."""
    kind = ABAQUS["C3D10"]
    conn = file_connectivity(sector.basis, kind)
    mat = sector.material
    lines = ["*HEADING", "ringdamper imported sector", "*NODE"]
    # ccx reads at most 20 characters a field
    lines += [f"{i + 1}, {x:.13g}, {y:.13g}, {z:.13g}" for i, (x, y, z) in enumerate(sector.nodes)]
    lines.append("*ELEMENT, TYPE=C3D10, ELSET=EALL")
    lines += [", ".join(str(v + 1) for v in [e, *row]) for e, row in enumerate(conn)]
    lines += _set_lines("LOW", sector.left_nodes) + _set_lines("HIGH", sector.right_nodes)
    # a dependent (high-face) node may not carry an SPC: its low-face partner, clamped too, holds it
    lines += _set_lines("FIX", np.setdiff1d(sector.fixed_nodes, sector.right_nodes))
    lines += ["*SURFACE, NAME=SLOW, TYPE=NODE", "LOW", "*SURFACE, NAME=SHIGH, TYPE=NODE", "HIGH",
              "*TIE, NAME=T1, CYCLIC SYMMETRY, ADJUST=NO", "SHIGH, SLOW",
              f"*CYCLIC SYMMETRY MODEL, N={sector.n_sectors}, NGRAPH=1, TIE=T1", "0., 0., 0., 0., 0., 1.",
              "*MATERIAL, NAME=M", "*ELASTIC", f"{mat['young_modulus']:.13g}, {mat['poisson_ratio']:.13g}",
              "*DENSITY", f"{mat['density']:.13g}", "*SOLID SECTION, ELSET=EALL, MATERIAL=M",
              "*BOUNDARY", "FIX, 1, 3"]
    if omega > 0.0:
        lines += ["*STEP, NLGEOM" if nlgeom else "*STEP", "*STATIC", "*DLOAD",
                  f"EALL, CENTRIF, {omega**2:.13g}, 0., 0., 0., 0., 0., 1.", "*END STEP", "*STEP, PERTURBATION"]
    else:
        lines.append("*STEP")
    lines += ["*FREQUENCY", f"{2 * n_modes}",
              f"*SELECT CYCLIC SYMMETRY MODES, NMIN=0, NMAX={sector.n_sectors // 2}", "*END STEP"]
    return "\n".join(lines) + "\n"


def read_dat_frequencies(text: str) -> dict[int, np.ndarray]:
    """Frequencies (Hz) per nodal diameter from a CalculiX .dat file's eigenvalue output: rows
    'ND, mode, eigenvalue, rad/time, cycles/time, imaginary part'. CalculiX solves the cosine and
    sine sectors together, so every mode appears twice; one of each pair is kept."""
    out = {}
    for block in text.split("E I G E N V A L U E   O U T P U T")[1:]:
        for line in block.split("P A R T I C I P A T I O N")[0].splitlines():
            parts = line.split()
            if len(parts) == 6 and parts[0].isdigit() and parts[1].isdigit():
                out.setdefault(int(parts[0]), []).append(float(parts[4]))
    return {nd: np.array(f[0::2]) for nd, f in out.items()}


def run_cyclic(sector, n_modes: int, omega: float = 0.0, nlgeom: bool = True, workdir=None) -> dict[int, np.ndarray]:
    """Run ``ccx`` on :func:`cyclic_deck` and return its frequencies per nodal diameter."""
    with tempfile.TemporaryDirectory(dir=workdir) as tmp:
        deck = Path(tmp) / "sector.inp"
        deck.write_text(cyclic_deck(sector, n_modes, omega, nlgeom))
        run = subprocess.run([CCX, "-i", "sector"], cwd=tmp, capture_output=True, text=True, timeout=600,
                             env={"OMP_NUM_THREADS": "1", "PATH": "/usr/bin:/bin"})
        dat = Path(tmp) / "sector.dat"
        if run.returncode != 0 or not dat.is_file():
            raise RuntimeError(f"ccx failed ({run.returncode}): {run.stdout[-2000:]} {run.stderr[-2000:]}")
        return read_dat_frequencies(dat.read_text())
