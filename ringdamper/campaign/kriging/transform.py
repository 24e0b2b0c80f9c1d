"""The output transforms of the Kriging models: the Gaussian process models z = T(y), predictions are
read back through T⁻¹.

* ``identity``: z = y; the prediction is the Kriging mean m, the band m ± 2s.
* ``log``, for outputs that physics keeps non-negative (|q_res,z|, ζ, γ):

      z = ln(y + c),      y = T⁻¹(z) = max(eᶻ − c, 0),      c = ``log_offset`` × max(y_train)

  per model (one c per output and amplitude, scale-free). The offset c keeps ζ = 0 (the stuck
  regime) finite; the clip at 0 makes the predictive distribution of y that of max(e^Z − c, 0),
  Z ~ N(m, s²): a shifted lognormal with an atom at 0 for the geometries predicted stuck. Quantiles
  go through a non-decreasing T⁻¹ exactly, so

      median = T⁻¹(m),      95.45 % band = [T⁻¹(m − 2s), T⁻¹(m + 2s)],

  all ≥ 0 for any m, s. The point prediction is the median (not the mean e^(m + s²/2) − c, which grows
  with s and would favour uncertain geometries in an optimum search; the median interpolates the
  training data like the Kriging mean). c → ∞ turns the transform into an affine map (the identity
  model, clipped at 0); c → 0 into a plain logarithm, which stretches the gap between a stuck ring
  (y = 0) and a sliding one into a jump. The default c = max(y) is the mildest of the values measured
  (z spans ln 2 over the data) and the closest to the identity's accuracy in cross-validation:
  docs/surrogate.md, *Positive outputs*.

The spread reported beside a prediction is (upper − lower) / 4: s itself for the identity, and for
the log transform (eᵐ⁺²ˢ − eᵐ⁻²ˢ)/4 ≈ eᵐ s, the delta-method standard deviation, where no bound is
clipped.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .gp import SIGMA_BAND

TRANSFORMS = ("identity", "log")
#: training values of a log model below −NEGATIVE_RTOL × the output scale are an error. Above it they are
#: the solver's noise around 0: a point that the dNNM's Newton converges to ζ = 0 (a ring still stuck,
#: reached by continuation) carries the error its tolerance leaves, |δξ| ≤ tol·ω, i.e. |δζ| ≤ tol/2 =
#: 5e-9 at the campaign's 1e-8 (seen: −2.8e-15, which a round-off bound of 1e-12 × ζ_max refused).
NEGATIVE_RTOL = 1e-6


@dataclass(frozen=True)
class Transform:
    """z = T(y) of one model (module doc); ``offset`` c (output units) for ``log``, 0 for ``identity``."""

    kind: str = "identity"
    offset: float = 0.0

    @classmethod
    def for_data(cls, kind: str, y: np.ndarray, log_offset: float, scale: float, name: str = "y") -> Transform:
        """The transform of training data ``y``: c = ``log_offset`` × max(y) (1 when no y is positive,
        where the model is the constant 0). A log model clips y at 0 (solver noise around ζ = 0); a value
        below -NEGATIVE_RTOL × ``scale`` (the output's largest |y| over the campaign) is an error
        naming ``name``."""
        if kind not in TRANSFORMS:
            raise ValueError(f"{name}: transform {kind!r}; allowed {TRANSFORMS}")
        if kind == "identity":
            return cls()
        y = np.asarray(y, dtype=float)
        if y.min() < -NEGATIVE_RTOL * scale:
            raise ValueError(f"{name}: transform 'log' needs non-negative data, smallest value {y.min():.3g}; "
                             "use surrogate.transform identity for this output")
        top = float(y.max())
        return cls("log", log_offset * top if top > 0.0 else 1.0)

    def forward(self, y: np.ndarray) -> np.ndarray:
        """z = T(y)."""
        y = np.asarray(y, dtype=float)
        return y if self.kind == "identity" else np.log(np.maximum(y, 0.0) + self.offset)

    def inverse(self, z: np.ndarray) -> np.ndarray:
        """y = T⁻¹(z), non-decreasing (quantiles of z map to quantiles of y)."""
        z = np.asarray(z, dtype=float)
        return z if self.kind == "identity" else np.maximum(np.exp(z) - self.offset, 0.0)

    def predictive(self, mean: np.ndarray, std: np.ndarray | None):
        """(point prediction, spread, lower, upper) in output units from the Kriging mean m and
        standard deviation s of z (module doc); the last three are None when ``std`` is None."""
        point = self.inverse(mean)
        if std is None:
            return point, None, None, None
        if self.kind == "identity":
            return point, std, mean - SIGMA_BAND * std, mean + SIGMA_BAND * std
        lower, upper = self.inverse(mean - SIGMA_BAND * std), self.inverse(mean + SIGMA_BAND * std)
        return point, (upper - lower) / (2.0 * SIGMA_BAND), lower, upper

    def units(self, units: str) -> str:
        """Units of z for an output in ``units``."""
        return units if self.kind == "identity" else "1"

    def describe(self, name: str, units: str) -> str:
        """z in words, for long names."""
        return name if self.kind == "identity" else f"ln(({name} + offset) / (1 {units}))"
