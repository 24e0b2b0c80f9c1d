"""Scalar summary of a backbone, for comparisons (surrogate against computed, ours against the
paper): the maximum modal damping ratio ζ_max, the amplitude |q_res,z| and normalised frequency ω0
there, and ω0 at the lowest and highest amplitude of the usable backbone."""
from __future__ import annotations

import numpy as np

from ..status import usable_status


def backbone_summary(q, omega0, zeta, status=None, max_level=np.inf) -> dict:
    """``zeta_max``, ``q_at_zeta_max`` [m], ``omega0_at_zeta_max``, ``omega0_low`` and
    ``omega0_high`` (first and last finite points) of a backbone given on one amplitude grid;
    points whose ``status`` is not usable (0 or 3) or not finite are left out. ζ_max is sought
    where |q_res,z| ≤ ``max_level`` [m] (the optimum criterion's range, ``exploration.optimum_max_level``),
    so that a prediction and a computation are summarised by the same rule."""
    q, omega0, zeta = (np.asarray(a, float) for a in (q, omega0, zeta))
    ok = np.isfinite(q) & np.isfinite(omega0) & np.isfinite(zeta)
    if status is not None:
        ok &= usable_status(status)
    if not ok.any():
        raise ValueError("the backbone has no usable point")
    idx = np.flatnonzero(ok)
    searched = idx[q[idx] <= max_level]
    if not searched.size:
        raise ValueError(f"the backbone has no usable point with |q_res,z| <= {max_level} m")
    i = searched[np.argmax(zeta[searched])]
    return {"zeta_max": float(zeta[i]), "q_at_zeta_max": float(q[i]),
            "omega0_at_zeta_max": float(omega0[i]), "omega0_low": float(omega0[idx[0]]),
            "omega0_high": float(omega0[idx[-1]]), "q_high": float(q[idx[-1]])}


def dnnm_summary(ds, max_level=np.inf) -> dict:
    """:func:`backbone_summary` of a ``dnnm.nc`` dataset."""
    return backbone_summary(ds.q_res_z.values, ds.omega0.values, ds.zeta.values, ds.status.values,
                            max_level)
