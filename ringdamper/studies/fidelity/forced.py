"""E-EBM against the forced-response curves that give the same resonance information.

The campaign's Table 3 (``frf/table3.csv``) holds, per forcing level and ring, the E-EBM resonant
|q_res,z| and the forced-response peak; the cost is the ``wall_time_s`` of the solves (attribute of
dnnm.nc and of each frf curve). One backbone gives the resonance at every forcing level; the forced
responses need one curve per level.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import xarray as xr


def eebm_vs_frf(table3: pd.DataFrame, dnnm_paths: dict, frf_paths: dict) -> list[dict]:
    """Rows per ring (name -> paths): cost of the backbone, of the curves, their ratio, and the
    largest and mean |amplitude difference| (%) of the forced peaks against the E-EBM."""
    rows = []
    for ring, dnnm in dnnm_paths.items():
        with xr.open_dataset(dnnm) as ds:
            t_dnnm = float(ds.attrs["wall_time_s"])
        t_frf = []
        for p in frf_paths[ring]:
            with xr.open_dataset(p) as ds:
                t_frf.append(float(ds.attrs["wall_time_s"]))
        diff = np.abs(table3[f"{ring}_frf_vs_eebm_pct"].to_numpy(float))
        rows.append({"ring": ring, "n_levels": len(t_frf), "dnnm_time_s": t_dnnm, "frf_time_s": float(np.sum(t_frf)),
                     "frf_per_level_s": float(np.mean(t_frf)), "cost_ratio": float(np.sum(t_frf) / t_dnnm),
                     "max_amplitude_error_pct": float(diff.max()), "mean_amplitude_error_pct": float(diff.mean())})
    return rows
