"""Harmonic balance on the contact coordinates (docs/nonlinear_core.md): the linear structure per
harmonic, receptances, the condensed residual, the dNNM by the EPMC, forced responses and their Hill
stability, and the E-EBM. Built on :mod:`ringdamper.nonlinear.solvers` and
:mod:`ringdamper.nonlinear.contact`."""
