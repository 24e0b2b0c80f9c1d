"""Parametric geometry: kappa -> bump shapes, the structured hexahedral sector mesh, contact pairs."""
