"""Nonlinear dynamics of the ring damper (paper §2.5, docs/nonlinear_core.md), in layers that import
one way, downwards (``tests/nonlinear/test_package_layers.py``):

* :mod:`ringdamper.nonlinear.fourier` (the Fourier convention),
  :mod:`ringdamper.nonlinear.normalisation` (the paper's ω0) and
  :mod:`ringdamper.nonlinear.solvers` (Newton, Krylov, continuation), side by side at the bottom;
* :mod:`ringdamper.nonlinear.contact`: friction contact and nonlinear elements by AFT;
* :mod:`ringdamper.nonlinear.harmonic_balance`: the condensed harmonic balance, the dNNM by the EPMC,
  forced responses, their stability and the E-EBM;
* :mod:`ringdamper.nonlinear.indicators` (truncation, separation, conditioning) and
  :mod:`ringdamper.nonlinear.time_domain` (shooting);
* :mod:`ringdamper.nonlinear.adaptive` (adaptive harmonic truncation), then
  :mod:`ringdamper.nonlinear.stage` (the dNNM stage of one geometry) at the top.

Import-free, so that ``ringdamper.nonlinear.fourier`` loads without the rest.
"""
