"""Benchmark of the surrogate stage on synthetic data of the campaign's size (``make bench``).

100 training geometries (27-point factorial + 73 LHS) × 30 amplitudes × 4 outputs = 120 Kriging models,
then the 50³ grid with predictive standard deviations, then Sobol indices (10⁴ base samples) of a cheap
function and of the surrogate at one amplitude (evaluated at every amplitude, as the caller does).
Smooth synthetic responses stand in for the dNNM outputs; their shape only changes the fit time
through the optimiser's iteration count.
"""

from __future__ import annotations

import itertools
import time

import numpy as np
import xarray as xr
from scipy.stats import qmc

from ringdamper.campaign import kriging, sensitivity


def synthetic_dataset(n_amplitudes: int = 30, seed: int = 0) -> xr.Dataset:
    """dataset.nc look-alike: ω0, ζ, γ, |q_res,z| smooth in κ, changing with the amplitude α."""
    factorial = np.array(list(itertools.product((-1.0, 0.0, 1.0), repeat=3)))
    lhs = 2.0 * qmc.LatinHypercube(d=3, rng=np.random.default_rng(seed)).random(73) - 1.0
    k = np.vstack([factorial, lhs])
    alpha = np.geomspace(1e-6, 3e-4, n_amplitudes)
    t = np.log(alpha / alpha[0])[None, :] / np.log(alpha[-1] / alpha[0])
    k1, k2, k3 = (k[:, i:i + 1] for i in range(3))
    zeta = 1e-3 * t * (1 - t) * (2 + k1 + 0.5 * np.sin(2 * k2) * k3 + 0.3 * k3**2)
    dims = ("geometry", "amplitude")
    return xr.Dataset(
        {"q_res_z": (dims, alpha * (1.0 + 0.1 * k1 - 0.05 * k2 * t)),
         "omega0": (dims, 1.0 + 0.02 * k1 - 0.01 * t * (1 + 0.3 * k2 + 0.2 * np.cos(2 * k3))),
         "zeta": (dims, zeta),
         "gamma": (dims, 40.0 * zeta * alpha / alpha[-1] * (1 + 0.2 * k1))},
        coords={"amplitude": alpha, **{f"kappa{i + 1}": ("geometry", k[:, i]) for i in range(3)}})


def run(settings: dict | None = None, grid_points: int = 50) -> dict:
    out = {}
    ds = synthetic_dataset()
    t = time.perf_counter()
    kds = kriging.fit_campaign(ds, settings=settings)
    out["fit_120_models_s"] = time.perf_counter() - t
    out["q2_min"] = float(np.nanmin(kds["q2"].values))
    t = time.perf_counter()
    surrogate = kriging.KrigingSurrogate(kds)
    out["load_factorise_s"] = time.perf_counter() - t
    axis = np.linspace(-1.0, 1.0, grid_points)
    grid = np.stack(np.meshgrid(axis, axis, axis, indexing="ij"), axis=-1).reshape(-1, 3)
    t = time.perf_counter()
    pred = surrogate.predict(grid, with_std=True)
    out[f"predict_grid_{grid_points}^3_with_std_s"] = time.perf_counter() - t
    out["grid_points"] = len(grid)
    out["predictions"] = int(sum(pred[o].size for o in kriging.OUTPUTS))
    del pred
    t = time.perf_counter()
    surrogate.predict(grid, with_std=False)
    out[f"predict_grid_{grid_points}^3_mean_only_s"] = time.perf_counter() - t
    box = [[-1.0, 1.0]] * 3
    for estimator in ("saltelli", "martinez"):
        t = time.perf_counter()
        sensitivity.sobol_indices(_cheap, box, n_base=10_000, estimator=estimator)
        out[f"sobol_{estimator}_1e4_cheap_function_s"] = time.perf_counter() - t
    t = time.perf_counter()
    sensitivity.sobol_indices(_cheap, box, n_base=10_000, estimator="saltelli", interval="bootstrap")
    out["sobol_saltelli_1e4_cheap_function_bootstrap200_s"] = time.perf_counter() - t
    outputs = ["omega0", "zeta", "gamma"]
    mid = len(kds["amplitude"]) // 2

    def at_mid_amplitude(x):
        pred = surrogate.predict(x, outputs=outputs, with_std=False)
        return np.column_stack([pred[o].values[mid] for o in outputs])

    t = time.perf_counter()
    sensitivity.sobol_indices(at_mid_amplitude, box, n_base=10_000, output_names=outputs)
    out["sobol_martinez_1e4_surrogate_3_outputs_all_amplitudes_s"] = time.perf_counter() - t
    t = time.perf_counter()
    sensitivity.sobol_indices_pce(at_mid_amplitude, box, output_names=outputs)
    out["sobol_pce_surrogate_3_outputs_s"] = time.perf_counter() - t
    return out


def _cheap(x: np.ndarray) -> np.ndarray:
    """Three cheap outputs (Ishigami-like) of the three parameters."""
    y = (np.sin(np.pi * x[:, 0]) + 7.0 * np.sin(np.pi * x[:, 1]) ** 2
         + 0.1 * (np.pi * x[:, 2]) ** 4 * np.sin(np.pi * x[:, 0]))
    return np.column_stack([y, x[:, 0] + x[:, 1] * x[:, 2], np.exp(x[:, 2])])


if __name__ == "__main__":
    import json

    print(json.dumps(run(), indent=2))
