"""Nonlinear forces and their AFT evaluation (docs/nonlinear_core.md §2): the play operator, the
isotropic Coulomb slider, the 3-D frictional contact pairs and the user's nonlinear elements. They
stand on :mod:`ringdamper.nonlinear.fourier` only."""
