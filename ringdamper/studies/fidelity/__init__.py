"""Fidelity study (make fidelity, docs/fidelity.md): every fidelity dial against its cost.

``dials``: the one-at-a-time cases; ``chain``: one case of the per-geometry chain, timed;
``quantities``: what users read off a backbone and its error; ``mesh``: mesh levels with Richardson
extrapolation; ``surrogate``: Kriging training-set size, LHS against a sequential design;
``summary``: the tables, the chosen settings and the campaign time.
"""
