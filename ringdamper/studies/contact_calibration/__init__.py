"""Calibration of the friction-contact parameters on the default ring (docs/design.md §2 "Contact pairs").

The paper does not give μ, kn, kt. They are chosen ONCE, on the default ring (κ = 0), inside the
physically plausible ranges of :data:`.trial.PLAUSIBLE`, so that the default ring's dNNM backbone
resembles the paper's §2.6 / Fig. 8 (:data:`.metrics.PAPER_TARGET`): maximum modal damping ratio
ζ_max ≈ 0.15 % at |q_res,z| ≈ 0.164 mm, where the normalised resonant frequency has dropped from
2.195 to 2.187 (−0.36 %), with ζ → 0 and ω0 constant at small amplitude. They are never tuned per
geometry.

* :mod:`.metrics`: what a trial measures, the summary of its backbone and its objective J against
  the paper's default ring;
* :mod:`.trial`: one trial, the default ring's backbone (static state, EPMC + E-EBM) for one
  ``contact:`` section and harmonic count H, and its row;
* :mod:`.dataset`: the stages and their results. A coarse grid over (μ, kn, kt/kn) at H = 1, a
  refined grid around the best coarse row, then the chosen set (``contact:`` of the configuration)
  and the runner-up at several H (harmonic truncation); the rows and backbones of a stage, and
  the curves of the study's figures.

The grids, the α grid and the runner-up are the ``studies.contact_calibration`` section of the
configuration; the rules of ``make studies`` run the stages (docs/calibration.md).
"""
