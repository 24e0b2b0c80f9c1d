"""Linear modal analysis of the rotating blisk + ring (paper §2.3, Figs. 3–5; docs/design.md §3.1).

* ``cyclic_modes``: eigenpairs of the ND-k sector, K_k phi = w^2 M_k phi (shift-invert Lanczos).
* ``classify``: families by where the strain energy lives: a mode with more than half of it in the
  ring is a ring mode ("ring"; only without contact); one whose blade strain energy is below half of
  the total is disk-dominated (1D, 2D, ...); blade modes are named from their shape: the tip's
  circumferential motion changes sign across the chord for torsion (1T); otherwise bending, 1B or 2B
  by the number of sign changes of the leading edge's circumferential motion along the height.
* ``nd_diagram`` / ``campbell``: frequencies against nodal diameter / speed with prestress.
* ``eo_crossing``: speed where a family's frequency meets the engine-order line f = EO Omega / 2 pi.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from scipy.optimize import brentq
from skfem import Basis

from ringdamper.fem.cyclic import cyclic_transform, nodal_diameter_phase, project
from ringdamper.fem.elasticity import tangent_stiffness
from ringdamper.fem.linalg import lowest_modes
from ringdamper.fem.model import INTORDER, SectorModel
from ringdamper.geometry.sector import PART_BLADE, PART_RING

SHIFT_HZ = 1.0  # shift-invert below the lowest mode of interest (the stuck model has no rigid mode)


@dataclass
class CyclicModes:
    nd: int
    frequency: np.ndarray   # (n_modes,) Hz
    shapes: np.ndarray      # (n_dofs, n_modes) complex, full sector DoFs, mass-normalised


def cyclic_modes(model: SectorModel, K: sp.spmatrix, M: sp.spmatrix, nd: int, n_modes: int,
                 sigma: float | None = None) -> CyclicModes:
    """Lowest ``n_modes`` modes of nodal diameter ``nd`` (phase ``sigma`` overrides 2 pi nd / N)."""
    sigma = nodal_diameter_phase(nd, model.n_sectors) if sigma is None else sigma
    T, _ = cyclic_transform(model.n_dofs, model.left_nodes, model.right_nodes, model.fixed_dofs,
                            model.sector_angle, sigma)
    Kk, Mk = project(T, K), project(T, M)
    w2, phi = lowest_modes(Kk, Mk, n_modes, shift=-(2 * np.pi * SHIFT_HZ) ** 2)
    return CyclicModes(nd=nd, frequency=np.sqrt(np.maximum(w2, 0.0)) / (2 * np.pi), shapes=T @ phi)


class FamilyClassifier:
    """Names modes 1B, 1T, 2B (blade), 1D (disk) or ring from energy fractions and blade shapes."""

    def __init__(self, model: SectorModel):
        self.model = model
        self.K_blade, sub = self._part_stiffness(PART_BLADE)
        self.K_ring, _ = self._part_stiffness(PART_RING)
        nodes = model.nodes
        blade_nodes = np.unique(sub.element_dofs)
        r = np.hypot(nodes[blade_nodes, 0], nodes[blade_nodes, 1])
        self.tip = blade_nodes[np.isclose(r, r.max(), atol=1e-6)]
        z = nodes[:, 2]
        self.leading = blade_nodes[np.isclose(z[blade_nodes], z[blade_nodes].min(), atol=1e-9)]
        self.leading = self.leading[np.argsort(np.hypot(nodes[self.leading, 0], nodes[self.leading, 1]))]

    def _part_stiffness(self, part):
        """Stiffness of one part's elements, and the sub-basis."""
        elements = np.flatnonzero(self.model.geometry.part == part)
        sub = Basis(self.model.geometry.mesh, self.model.basis.elem, elements=elements,
                    intorder=INTORDER[self.model.element_order])
        mat = self.model.material
        return tangent_stiffness(sub, mat["young_modulus"], mat["poisson_ratio"]), sub

    def _energy_fraction(self, K_part, K: sp.spmatrix, phi: np.ndarray) -> float:
        return float(np.real(phi.conj() @ (K_part @ phi)) / np.real(phi.conj() @ (K @ phi)))

    def blade_energy_fraction(self, K: sp.spmatrix, phi: np.ndarray) -> float:
        return self._energy_fraction(self.K_blade, K, phi)

    def _circumferential(self, phi: np.ndarray, nodes: np.ndarray) -> np.ndarray:
        """Real circumferential displacement (phase of the largest blade motion removed)."""
        p = self.model.nodes[nodes]
        theta = np.arctan2(p[:, 1], p[:, 0])
        u = phi.reshape(-1, 3)[nodes]
        v = -np.sin(theta) * u[:, 0] + np.cos(theta) * u[:, 1]
        ref = v[np.argmax(np.abs(v))]
        return np.real(v * np.conj(ref) / abs(ref))

    def label(self, K: sp.spmatrix, phi: np.ndarray) -> str:
        if self._energy_fraction(self.K_ring, K, phi) > 0.5:
            return "ring"
        if self.blade_energy_fraction(K, phi) < 0.5:
            return "1D"
        z = self.model.nodes[self.tip, 2]
        v_tip = self._circumferential(phi, self.tip)
        zc = z - z.mean()
        torsion = abs(v_tip @ zc) / (np.linalg.norm(v_tip) * np.linalg.norm(zc) + 1e-300)
        if torsion > 0.7:
            return "1T"
        v = self._circumferential(phi, self.leading)
        v = v[np.abs(v) > 0.05 * np.abs(v).max()]
        changes = int(np.sum(np.diff(np.sign(v)) != 0))
        return {0: "1B", 1: "2B"}.get(changes, "blade")


def _number_families(labels: list[str]) -> list[str]:
    """Within one ND: successive disk-dominated modes are 1D, 2D, 3D, ...; a blade family name goes
    to its lowest mode only (higher modes of the same shape class, e.g. 2T, stay "blade")."""
    count, seen, out = 0, set(), []
    for lab in labels:
        if lab == "1D":
            count += 1
            lab = f"{count}D"
        elif lab in seen and lab != "ring":
            lab = "blade"
        seen.add(lab)
        out.append(lab)
    return out


def labelled_modes(model: SectorModel, K: sp.spmatrix, nd: int, n_modes: int,
                   classifier: FamilyClassifier):
    """(frequency Hz, family labels, blade strain-energy fractions) of one nodal diameter."""
    modes = cyclic_modes(model, K, model.M, nd, n_modes)
    phis = modes.shapes.T
    blade = np.array([classifier.blade_energy_fraction(K, phi) for phi in phis])
    labels = _number_families([classifier.label(K, phi) for phi in phis])
    return modes.frequency, labels, blade


def nd_diagram(model: SectorModel, K: sp.spmatrix, nds, n_modes: int):
    """Frequencies (Hz), labels and blade energy fractions for each nodal diameter."""
    clf = FamilyClassifier(model)
    rows = [labelled_modes(model, K, nd, n_modes, clf) for nd in nds]
    return (np.array([r[0] for r in rows]), np.array([r[1] for r in rows], dtype=object),
            np.array([r[2] for r in rows]))


def campbell(model: SectorModel, K_contact: sp.spmatrix, speeds_rad_s, nd: int, n_modes: int):
    """Frequencies (Hz) and labels of ND ``nd`` against speed, with prestress (§2.3, Fig. 5)."""
    from ringdamper.fem.prestress import prestressed_stiffness

    clf = FamilyClassifier(model)
    rows = [labelled_modes(model, prestressed_stiffness(model, w, K_contact), nd, n_modes, clf)
            for w in speeds_rad_s]
    return np.array([r[0] for r in rows]), np.array([r[1] for r in rows], dtype=object)


def family_frequency(freq_row: np.ndarray, label_row, family: str) -> float:
    """Frequency of the first mode of ``family`` in one ND (nan when absent)."""
    hits = [f for f, lab in zip(freq_row, label_row) if lab == family]
    return hits[0] if hits else np.nan


def eo_crossing(speeds_rad_s: np.ndarray, family_hz: np.ndarray, engine_order: int) -> tuple[float, float]:
    """Speed (rad/s) and frequency (Hz) where f(Omega) = EO Omega / 2 pi.

    f(Omega)^2 is fitted as a + b Omega^2 (exact for linear prestress, Southwell's form) and the root
    of f(Omega) - EO Omega / 2 pi is found with Brent's method inside the computed speed range.
    """
    a, b = np.polynomial.polynomial.polyfit(speeds_rad_s**2, family_hz**2, 1)

    def gap(w):
        return np.sqrt(a + b * w**2) - engine_order * w / (2 * np.pi)

    lo, hi = speeds_rad_s.min(), 1.5 * speeds_rad_s.max()  # modest extrapolation of Southwell's fit
    if gap(lo) * gap(hi) > 0:
        raise ValueError(f"EO {engine_order} line does not cross the family between "
                         f"{lo * 60 / (2 * np.pi):.0f} and {hi * 60 / (2 * np.pi):.0f} rpm")
    w = brentq(gap, lo, hi, xtol=1e-10)
    return w, engine_order * w / (2 * np.pi)
