"""Synthetic dnnm.nc files with analytic backbones, for the campaign-analytics tests.

Backbone of geometry kappa on the amplitude grid alpha (log-spaced):
    |q_res,z| = c(kappa) alpha,                 c = 2.27 (1 + 0.05 kappa1)   (m per kg^0.5 m)
    zeta      = zeta_peak(kappa) b(alpha),      b = exp(-(ln alpha - ln 3e-5)^2 / 2),
    zeta_peak = 3e-3 (1 - |kappa - KAPPA_STAR|^2 / 12)   (maximum at KAPPA_STAR)
    omega0    = 2.195 - 0.01 (1 + 0.3 kappa1) s(alpha),   s a logistic step in ln alpha
    gamma     = 2e4 alpha omega0^2 (zeta + 1e-4)
so every output is smooth in kappa and the geometry of maximum zeta_max is KAPPA_STAR.
"""
from __future__ import annotations

import numpy as np
import pandas as pd
import xarray as xr

from ringdamper.io import write_netcdf
from ringdamper.nonlinear.stage import DNNM_VARIABLES
from ringdamper.nonlinear.stage import dnnm_dataset as stage_dataset

KAPPA_STAR = np.array([0.4, -0.3, 0.2])
ALPHA_PEAK = 3e-5


def quadratic_peak(k: np.ndarray) -> float:
    """zeta_peak of the module docstring: largest at KAPPA_STAR."""
    return 3e-3 * (1 - np.sum((k - KAPPA_STAR) ** 2) / 12)


def backbone(kappa, alpha, zeta_peak=quadratic_peak) -> dict:
    """Analytic outputs (module docstring) of geometry ``kappa`` at amplitudes ``alpha``, with the peak
    damping ``zeta_peak(kappa)`` (default :func:`quadratic_peak`)."""
    k = np.asarray(kappa, float)
    la = np.log(alpha)
    q = 2.27 * (1 + 0.05 * k[0]) * alpha
    zeta_peak = zeta_peak(k)
    zeta = zeta_peak * np.exp(-0.5 * (la - np.log(ALPHA_PEAK)) ** 2)
    omega0 = 2.195 - 0.01 * (1 + 0.3 * k[0]) / (1 + np.exp(-(la - np.log(2e-5))))
    gamma = 2e4 * alpha * omega0 ** 2 * (zeta + 1e-4)
    return {"q_res_z": q, "zeta": zeta, "omega0": omega0, "gamma": gamma}


def dnnm_dataset(kappa, alpha, status=None, n_pairs: int = 2, zeta_peak=quadratic_peak) -> xr.Dataset:
    """The dnnm.nc of the analytic backbone, written through the dNNM stage's own declaration
    (``status`` per amplitude, default 0): the four analytic outputs, the frequency in Hz and a
    constant phase; the per-pair energies and diagnostics, which the analytics do not read, are 0."""
    b = backbone(kappa, alpha, zeta_peak)
    status = np.zeros(alpha.size, np.int8) if status is None else np.asarray(status, np.int8)
    size = {"amplitude": alpha.size, "pair": n_pairs}
    values = {k: np.zeros([size[d] for d in np.atleast_1d(dims)])
              for k, (dims, _, _) in DNNM_VARIABLES.items()}
    values.update(b, frequency=543.0 * b["omega0"], phi=np.full(alpha.size, -1.5),
                  q_res_z_h1=b["q_res_z"])
    return stage_dataset(alpha, n_pairs, values, status, {"kappa": np.asarray(kappa, float)})


def design(n_training: int, n_validation: int, seed: int = 1) -> pd.DataFrame:
    """samples.csv-like table: corners + random training points, random validation points."""
    rng = np.random.default_rng(seed)
    corners = np.array([[a, b, c] for a in (-1, 1) for b in (-1, 1) for c in (-1, 1)], float)
    train = np.vstack([corners, rng.uniform(-1, 1, (n_training - 8, 3))])
    val = rng.uniform(-1, 1, (n_validation, 3))
    rows = [(f"t{i:03d}", *k, "training") for i, k in enumerate(train)]
    rows += [(f"v{i:03d}", *k, "validation") for i, k in enumerate(val)]
    return pd.DataFrame(rows, columns=["gid", "kappa1", "kappa2", "kappa3", "split"])


def write_campaign(root, samples: pd.DataFrame, alpha, overrides=None) -> dict:
    """Write results/geometry/{gid}/dnnm.nc of every sample under ``root`` (``overrides``: gid ->
    dataset to write instead); returns gid -> path."""
    paths = {}
    for row in samples.itertuples():
        path = root / "geometry" / row.gid / "dnnm.nc"
        ds = (overrides or {}).get(row.gid)
        write_netcdf(ds if ds is not None else dnnm_dataset([row.kappa1, row.kappa2, row.kappa3], alpha), path)
        paths[row.gid] = path
    return paths
