"""Three-step model reduction of the blisk + ring sector (paper §2.5.1; docs/design.md §3.3,
docs/reduction.md): Craig–Bampton, Mead's cyclic constraint per harmonic's nodal diameter, interface
reduction; the reduced.nc contract and the reduction stage of one geometry.
"""

from .reduced import (
    ModalBasis,
    ReducedHarmonic,
    ReducedSector,
    eigenfrequencies,
    modal_basis,
    modal_stuck_frequencies,
    reduce_sector,
    reduced_dataset,
    stuck_frequencies,
    stuck_matrices,
)

__all__ = ["ModalBasis", "ReducedHarmonic", "ReducedSector",
           "eigenfrequencies", "modal_basis", "modal_stuck_frequencies",
           "reduce_sector", "reduced_dataset", "stuck_frequencies", "stuck_matrices"]
