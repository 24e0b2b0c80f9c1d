"""Training values moved within the solver's tolerance at the held points (status 3), for the stop rule's
noise tests. Held points move by up to 0.4 % in zeta between solver variants that converge the other
points to the same solutions within the Newton tolerance (docs/nonlinear_core.md §4.1); zeta and gamma
(the dissipation, which follows zeta) of a held point are moved by that share."""
import numpy as np

HELD_TOLERANCE = 4e-3
HELD_OUTPUTS = ("zeta", "gamma")


def moved_held(rings, train: np.ndarray, sign: float):
    """``rings`` with zeta and gamma of every held point of the rings ``train`` (bool over the
    geometries) scaled by 1 ± HELD_TOLERANCE, the signs alternating along the points (``sign`` = -1:
    the opposite pattern), and the number of points moved."""
    held = (rings.held.values == 1) & train[:, None]
    pattern = sign * np.where(np.cumsum(held.ravel()).reshape(held.shape) % 2 == 0, 1.0, -1.0)
    moved = rings.copy()
    for o in HELD_OUTPUTS:
        moved[o] = rings[o].where(~held, rings[o] * (1 + HELD_TOLERANCE * pattern))
    return moved, int(held.sum())
