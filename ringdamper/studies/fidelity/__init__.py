"""Fidelity study (make fidelity, docs/fidelity.md): every fidelity dial against its cost and error,
mesh levels with Richardson extrapolation, the surrogate's training-set size, and the summary tables.
"""
