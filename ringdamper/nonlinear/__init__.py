"""Nonlinear dynamics of the ring damper (paper §2.5, docs/nonlinear_core.md): friction contact by
AFT, harmonic balance, continuation, the dNNM by the EPMC, the E-EBM, forced responses, and the dNNM
stage of one geometry.

Import-free, so that ``ringdamper.nonlinear.fourier`` loads without the rest.
"""
