"""Three-step model reduction of the blisk + ring sector (paper §2.5.1; docs/design.md §3.3).

1. ``craig_bampton``: Craig–Bampton on the real sector (bore clamped), retained = contact pairs,
   blade-tip node, both cyclic faces (``partition``).
2. ``cyclic``: Mead's constraint per harmonic's nodal diameter -> Hermitian (K_h, M_h).
3. ``interface``: partial interface modes of the remaining left-face DoFs.
``reduced``: the chain, the modal basis, the stuck contact and the reduced.nc contract.
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
