"""Prediction from ``kriging.nc`` alone (no refit): every model rebuilt from its stored hyperparameters.

For each model the correlation matrix R = LLᵀ of its training inputs is factorised once at load
(:class:`.gp.GPModel`); the mean and standard deviation at x₀ are then (paper Eq. 8, variance in :mod:`.gp`)

    ŷ(x₀) = β + r₀ᵀ R⁻¹ (y - β1),      s(x₀) = √ψ σ √(1 + ν - ‖L⁻¹r₀‖² + (1 - 1ᵀR⁻¹r₀)² / (1ᵀR⁻¹1)),

with ψ the stored leave-one-out variance factor (*variance calibration* in :mod:`.gp`; ψ = 1, the ML
variance, when ``calibrated`` is False). Models sharing a training set share the coordinate differences
between the prediction points and the training inputs, and the points are processed in chunks.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from ...io import variable
from .campaign import PARAMETERS, STATUS_UNFITTED
from .gp import GPModel, _squared_differences


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
        kappa = ds["kappa"].transpose("geometry", "parameter").values
        mask = ds["training_mask"].transpose("amplitude", "geometry").values.astype(bool)
        self.groups = {}  # training inputs (bytes) -> [(output, amplitude index, GPModel)]
        for io, out in enumerate(self.outputs):
            y = ds[out].transpose("amplitude", "geometry").values
            for ia in range(ds.sizes["amplitude"]):
                if int(ds["status"].values[io, ia]) == STATUS_UNFITTED:
                    continue
                rows = mask[ia]
                model = GPModel(str(ds["kernel"].values[io, ia]), ds["scale"].values[io, ia],
                                ds[f"{out}_sigma"].values[ia], ds["nugget"].values[io, ia],
                                ds[f"{out}_beta"].values[ia], kappa[rows], y[ia, rows],
                                ds[f"{out}_variance_factor"].values[ia] if calibrated else 1.0)
                self.groups.setdefault(kappa[rows].tobytes(), []).append((out, ia, model))

    def predict(self, X, outputs=None, with_std: bool = True, chunk_size: int = 1024) -> xr.Dataset:
        """Dataset with ``<output>`` and ``<output>_std`` (amplitude, point) at X (m, 3); NaN where no
        model was fitted. Work is chunked in m (memory ~ 6 chunk_size × N doubles, N training points)."""
        X = np.atleast_2d(np.asarray(X, dtype=float))
        if X.ndim != 2 or X.shape[1] != len(PARAMETERS) or not np.all(np.isfinite(X)):
            raise ValueError(f"X must be a finite (m, {len(PARAMETERS)}) array, got shape {X.shape}")
        outputs = self.outputs if outputs is None else list(outputs)
        unknown = [o for o in outputs if o not in self.outputs]
        if unknown:
            raise ValueError(f"outputs {unknown} not in the surrogate; available {self.outputs}")
        n_amp, m = len(self.amplitude), len(X)
        mean = {o: np.full((n_amp, m), np.nan) for o in outputs}
        std = {o: np.full((n_amp, m), np.nan) for o in outputs}
        for start in range(0, m, chunk_size):
            sl = slice(start, min(start + chunk_size, m))
            for group in self.groups.values():
                todo = [(out, ia, model) for out, ia, model in group if out in mean]
                if not todo:
                    continue
                sq = _squared_differences(X[sl], todo[0][2].x)
                for out, ia, model in todo:
                    mean[out][ia, sl], sd = model.predict(X[sl], with_std, sq)
                    if with_std:
                        std[out][ia, sl] = sd
        data = {}
        for o in outputs:
            data[o] = variable(("amplitude", "point"), mean[o], self.units[o], f"Kriging prediction of {o}")
            if with_std:
                data[f"{o}_std"] = variable(("amplitude", "point"), std[o], self.units[o],
                                            f"Kriging predictive standard deviation of {o}")
        coords = {"amplitude": self.amplitude,
                  **{p: variable("point", X[:, k], "1", f"shape parameter {p}") for k, p in enumerate(PARAMETERS)}}
        return xr.Dataset(data, coords=coords)


def predict(kriging: xr.Dataset, X, outputs=None, with_std: bool = True, chunk_size: int = 1024) -> xr.Dataset:
    """Predictions of a ``kriging.nc`` Dataset at X (m, 3); see KrigingSurrogate.predict. For repeated
    calls build the KrigingSurrogate once (it factorises every model)."""
    return KrigingSurrogate(kriging).predict(X, outputs, with_std, chunk_size)
