"""The surrogate's prediction at the optimum against the backbone computed there (paper §3.4: the
optimum found on the Kriging models is a real geometry, run through the whole chain).

Compared: the summary figures of :mod:`ringdamper.campaign.summary` (ζ_max, |q_res,z| and ω0 at
ζ_max, ω0 at the lowest and highest amplitude) and, per output, the RMS and largest error over the
common amplitude grid where both the prediction and the computed point are usable.
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from ..status import usable_status
from .summary import backbone_summary, dnnm_summary

OUTPUTS = ("q_res_z", "omega0", "zeta", "gamma")


def predicted_backbone(kriging, kappa) -> dict:
    """Kriging prediction (median), spread and 95.45 % band of every output on the amplitude grid at
    ``kappa``: ``{name: array, name_std: array, name_lower: array, name_upper: array}``."""
    from .kriging import predict

    pred = predict(kriging, np.asarray(kappa, float)[None, :], outputs=OUTPUTS).isel(point=0)
    return {name: pred[name].values for name in pred.data_vars}


def surrogate_vs_computed(predicted: dict, computed, max_level=np.inf) -> pd.DataFrame:
    """Table: predicted and computed summary figures with their error (relative: predicted /
    computed − 1), then per output the RMS and largest error over the amplitudes where both are
    usable (relative: to the largest computed magnitude); ``predicted``: arrays on the amplitude grid
    of ``computed``, a dnnm.nc dataset; ζ_max of both sought up to |q_res,z| = ``max_level`` [m]."""
    p = backbone_summary(predicted["q_res_z"], predicted["omega0"], predicted["zeta"], max_level=max_level)
    c = dnnm_summary(computed, max_level)
    rows = [{"quantity": k, "predicted": p[k], "computed": c[k], "error": p[k] - c[k],
             "relative error (%)": 100 * (p[k] / c[k] - 1)} for k in c]
    ok = usable_status(computed.status.values)
    for name in OUTPUTS:
        y = computed[name].values
        both = ok & np.isfinite(y) & np.isfinite(predicted[name])
        err = predicted[name][both] - y[both]
        rows.append({"quantity": f"{name}: RMS error over {int(both.sum())} amplitudes",
                     "predicted": np.nan, "computed": np.nan, "error": float(np.sqrt(np.mean(err ** 2))),
                     "relative error (%)": 100 * float(np.sqrt(np.mean(err ** 2)) / np.abs(y[both]).max())})
        rows.append({"quantity": f"{name}: largest error", "predicted": np.nan, "computed": np.nan,
                     "error": float(err[np.argmax(np.abs(err))]),
                     "relative error (%)": 100 * float(np.abs(err).max() / np.abs(y[both]).max())})
    return pd.DataFrame(rows)
