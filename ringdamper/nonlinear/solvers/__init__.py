"""Generic nonlinear solvers (docs/nonlinear_core.md): Jacobians as matrices or operators, lagged
Krylov solves, Newton–Raphson and predictor–corrector continuation. They know nothing of contact or
harmonics: the bottom layer of :mod:`ringdamper.nonlinear`."""
