"""Time-domain reference for the harmonic balance: shooting on the autonomous system
(docs/nonlinear_core.md §4.4)."""
