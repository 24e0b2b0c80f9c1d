"""Harmonic balance core (DESIGN §3.4–3.5): Fourier/AFT operators (:mod:`.fourier`), the
per-harmonic linear structure (:mod:`.structure`), the residual condensed onto the contact
coordinates (:mod:`.condensed`), Newton and continuation (:mod:`.newton`, :mod:`.continuation`),
the EPMC / dNNM (:mod:`.epmc`) and forced problems (:mod:`.forced`). See docs/nonlinear_core.md.

Deliberately import-free: :mod:`ringdamper.contact.friction` imports :mod:`.fourier`.
"""
