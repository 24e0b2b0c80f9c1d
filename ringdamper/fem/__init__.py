"""Finite-element model of the sector: assembly, prestress, cyclic symmetry."""
