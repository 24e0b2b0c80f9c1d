"""Indicators of a computed backbone (docs/nonlinear_core.md §4.3, §4.6; docs/method_limits.md):
harmonic truncation (and the estimate of what raising it would change), contact separation and the
conditioning of the Newton Jacobian."""
