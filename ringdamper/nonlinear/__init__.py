"""Nonlinear dynamics of the ring damper (paper §2.5, docs/nonlinear_core.md), in the order of the
method chain:

* :mod:`.friction`: the 3-D friction contact element (Jenkins / Coulomb, AFT) and its stuck
  linearisation;
* :mod:`.fourier`: Fourier/AFT operators; :mod:`.structure`: the per-harmonic linear structure;
* :mod:`.condensed`: the harmonic balance residual condensed onto the contact coordinates;
* :mod:`.newton`, :mod:`.continuation`: the generic solver and continuation (no physics); the
  statuses they give every point are in :mod:`ringdamper.status`;
* :mod:`.epmc`: the extended periodic motion concept (dNNM); :mod:`.eebm`: the extended energy
  balance method; :mod:`.forced`, :mod:`.frf`: the forced response and its resonance peak;
  :mod:`.response`: response measures;
* :mod:`.normalisation`: the paper's normalised frequency;
* :mod:`.stage`: the dNNM stage of one geometry (reduced.nc + static.nc -> dnnm.nc).

Test systems: :mod:`.jenkins_chains`, the seeded family of spring–mass chains with Jenkins elements.

Import-free, so that ``ringdamper.nonlinear.fourier`` loads without the rest.
"""
