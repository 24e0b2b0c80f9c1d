"""Prediction from ``kriging.nc`` alone (no refit): every model rebuilt from its stored hyperparameters.

For each model the correlation matrix R = LLᵀ of its training inputs is factorised once at load
(:class:`.gp.GPModel`); the mean and standard deviation at x₀ are then (paper Eq. 8, variance in :mod:`.gp`)

    ŷ(x₀) = β + r₀ᵀ R⁻¹ (y - β1),      s(x₀) = √ψ σ √(1 + ν - ‖L⁻¹r₀‖² + (1 - 1ᵀR⁻¹r₀)² / (1ᵀR⁻¹1)),

with ψ the stored leave-one-out variance factor (*variance calibration* in :mod:`.gp`; ψ = 1, the ML
variance, when ``calibrated`` is False). ŷ and s belong to the transformed output z = T(y) of each model
(:mod:`.transform`); :meth:`KrigingSurrogate.predict` returns the output itself:

    <output>        T⁻¹(ŷ)                         the median (the Kriging mean for the identity)
    <output>_lower  T⁻¹(ŷ − 2s)                    the central 95.45 % predictive band, whose bounds
    <output>_upper  T⁻¹(ŷ + 2s)                    are the 2.275 % and 97.725 % quantiles
    <output>_std    (upper − lower) / 4            s for the identity; ≈ eŷ s for the log

and ``latent=True`` returns ŷ and s themselves (for probabilities: P(y > t) = 1 − Φ((T(t) − ŷ)/s),
t ≥ 0, with T of :meth:`KrigingSurrogate.transform`). Models sharing a training set share the coordinate
differences between the prediction points and the training inputs, and the points are processed in chunks.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from ...io import variable
from .campaign import PARAMETERS, STATUS_UNFITTED
from .gp import GPModel, _squared_differences
from .transform import Transform


class KrigingSurrogate:
    """All models of a ``kriging.nc`` Dataset, factorised once, for repeated vectorised prediction.
    ``calibrated``: predictive variances scaled by each model's leave-one-out factor (module doc);
    False gives the plain ML variance."""

    def __init__(self, ds: xr.Dataset, calibrated: bool = True):
        self.outputs = [str(o) for o in ds["output"].values]
        missing = [f"{o}_variance_factor" for o in self.outputs if f"{o}_variance_factor" not in ds]
        if calibrated and missing:
            raise ValueError(f"kriging.nc lacks {missing} (written before the variance calibration): "
                             "refit it (snakemake --forcerun kriging)")
        self.amplitude = ds["amplitude"]
        self.units = {o: ds[o].attrs.get("units", "1") for o in self.outputs}
        self.latent_units = {o: ds[f"{o}_beta"].attrs.get("units", self.units[o]) for o in self.outputs}
        kappa = ds["kappa"].transpose("geometry", "parameter").values
        mask = ds["training_mask"].transpose("amplitude", "geometry").values.astype(bool)
        self.groups = {}  # training inputs (bytes) -> [(output, amplitude index, GPModel)]
        self.transforms = {}  # (output, amplitude index) -> Transform of the fitted models
        for io, out in enumerate(self.outputs):
            y = ds[out].transpose("amplitude", "geometry").values
            for ia in range(ds.sizes["amplitude"]):
                if int(ds["status"].values[io, ia]) == STATUS_UNFITTED:
                    continue
                rows = mask[ia]
                transform = (Transform(str(ds["transform"].values[io, ia]), float(ds[f"{out}_offset"].values[ia]))
                             if "transform" in ds else Transform())
                model = GPModel(str(ds["kernel"].values[io, ia]), ds["scale"].values[io, ia],
                                ds[f"{out}_sigma"].values[ia], ds["nugget"].values[io, ia],
                                ds[f"{out}_beta"].values[ia], kappa[rows], transform.forward(y[ia, rows]),
                                ds[f"{out}_variance_factor"].values[ia] if calibrated else 1.0)
                self.transforms[out, ia] = transform
                self.groups.setdefault(kappa[rows].tobytes(), []).append((out, ia, model))

    def transform(self, output: str, amplitude_index: int) -> Transform:
        """The transform z = T(y) of the model of ``output`` at amplitude index ``amplitude_index``
        (identity for a model that was not fitted)."""
        return self.transforms.get((output, amplitude_index), Transform())

    def predict(self, X, outputs=None, with_std: bool = True, chunk_size: int = 1024,
                latent: bool = False) -> xr.Dataset:
        """Dataset (amplitude, point) at X (m, 3) of ``<output>`` (the median), and with ``with_std``
        ``<output>_std``, ``<output>_lower`` and ``<output>_upper`` (the 95.45 % band), all in output
        units (module doc); NaN where no model was fitted. ``latent``: ``<output>`` and ``<output>_std``
        are the Kriging mean ŷ and standard deviation s of the transformed output z = T(y) instead.
        Work is chunked in m (memory ~ 6 chunk_size × N doubles, N training points)."""
        X = np.atleast_2d(np.asarray(X, dtype=float))
        if X.ndim != 2 or X.shape[1] != len(PARAMETERS) or not np.all(np.isfinite(X)):
            raise ValueError(f"X must be a finite (m, {len(PARAMETERS)}) array, got shape {X.shape}")
        outputs = self.outputs if outputs is None else list(outputs)
        unknown = [o for o in outputs if o not in self.outputs]
        if unknown:
            raise ValueError(f"outputs {unknown} not in the surrogate; available {self.outputs}")
        n_amp, m = len(self.amplitude), len(X)
        kinds = ("", "_std", "_lower", "_upper") if with_std and not latent else ("", "_std") if with_std else ("",)
        values = {o + k: np.full((n_amp, m), np.nan) for o in outputs for k in kinds}
        for start in range(0, m, chunk_size):
            sl = slice(start, min(start + chunk_size, m))
            for group in self.groups.values():
                todo = [(out, ia, model) for out, ia, model in group if out in outputs]
                if not todo:
                    continue
                sq = _squared_differences(X[sl], todo[0][2].x)
                for out, ia, model in todo:
                    mean, sd = model.predict(X[sl], with_std, sq)
                    parts = (mean, sd) if latent else self.transforms[out, ia].predictive(mean, sd)
                    for k, part in zip(kinds, parts):
                        values[out + k][ia, sl] = part
        data = {}
        for o in outputs:
            u = self.latent_units[o] if latent else self.units[o]
            what = f"T({o}), the transformed" if latent else o
            data[o] = variable(("amplitude", "point"), values[o], u,
                               f"Kriging mean of {what}" if latent else f"Kriging prediction (median) of {o}")
            if with_std:
                data[f"{o}_std"] = variable(("amplitude", "point"), values[f"{o}_std"], u,
                                            f"Kriging standard deviation of {what}" if latent else
                                            f"Kriging predictive spread of {o}: (upper - lower) / 4")
            if with_std and not latent:
                for side, q in (("lower", "2.275"), ("upper", "97.725")):
                    data[f"{o}_{side}"] = variable(("amplitude", "point"), values[f"{o}_{side}"], self.units[o],
                                                   f"{side} bound of the 95.45 % Kriging band of {o} "
                                                   f"({q} % quantile)")
        coords = {"amplitude": self.amplitude,
                  **{p: variable("point", X[:, k], "1", f"shape parameter {p}") for k, p in enumerate(PARAMETERS)}}
        return xr.Dataset(data, coords=coords)


def predict(kriging: xr.Dataset, X, outputs=None, with_std: bool = True, chunk_size: int = 1024,
            latent: bool = False) -> xr.Dataset:
    """Predictions of a ``kriging.nc`` Dataset at X (m, 3); see KrigingSurrogate.predict. For repeated
    calls build the KrigingSurrogate once (it factorises every model)."""
    return KrigingSurrogate(kriging).predict(X, outputs, with_std, chunk_size, latent)
