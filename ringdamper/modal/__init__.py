"""Linear modal analysis of the rotating blisk + ring (paper §2.3): ND and Campbell diagrams, mode
families, the engine-order crossing, and the campaign's modal stage."""
