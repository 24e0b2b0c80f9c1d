"""Status codes of the nonlinear results, part of their file contract and read by every layer: one
per amplitude point in dnnm.nc and the campaign dataset, one per curve in the forced-response files
(the ``status`` variable, with its ``reason``).

What a status means for a reader of a result:

* ``0`` :attr:`Status.CONVERGED`: a solution (for a forced response: the curve crossed the whole
  frequency band); use it.
* ``1`` :attr:`Status.NO_CONVERGENCE`: the continuation stopped there (``reason`` says why, mostly
  a step fallen below its minimum and the step test it failed): no solution at that point (NaN);
  a forced-response curve ends before the end of its band.
* ``2`` :attr:`Status.NOT_REACHED`: the continuation stopped before this point; NaN.
* ``3`` :attr:`Status.DRIFT`: a solution whose free body (the ring) is not in mean rigid-body
  equilibrium, held by the gauge (the ring would ratchet); kept, and flagged (``held`` in the
  campaign dataset).
* ``4`` :attr:`Status.MAX_POINTS`: a forced-response curve whose arc-length point budget ran out
  before the end of its band.
* ``99`` :data:`CHAIN_FAILED`: the geometry's chain failed before the dNNM; every point carries
  it, every output is NaN and the file's ``reason`` says why.

:data:`USABLE_STATUS` (0 and 3) are the points every reader keeps; :func:`usable_status` tests it.
"""
from __future__ import annotations

from enum import IntEnum

import numpy as np


class Status(IntEnum):
    """Per-point status of a continuation (0 = converged), stored with every result."""

    CONVERGED = 0
    NO_CONVERGENCE = 1       # step size fell below its minimum
    NOT_REACHED = 2          # continuation stopped before this point
    DRIFT = 3                # converged, but a free body is not in mean equilibrium (ratchets)
    MAX_POINTS = 4           # arc-length budget exhausted before the end of the range


#: Status of every point of a geometry whose chain failed before the dNNM.
CHAIN_FAILED = 99

#: The statuses of the points that are solutions, which every reader of a result keeps: converged (0),
#: and converged with the ring's mean rigid-body equilibrium held by the gauge (3, flagged).
USABLE_STATUS = (int(Status.CONVERGED), int(Status.DRIFT))


def usable_status(status) -> np.ndarray:
    """Per point, whether its ``status`` is one of :data:`USABLE_STATUS`."""
    return np.isin(status, USABLE_STATUS)
