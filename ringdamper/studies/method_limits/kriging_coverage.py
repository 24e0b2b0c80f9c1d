"""Coverage of the Kriging 95.45 % band against the training size and near the design-space boundary.

For each training size ``n`` a seeded random subset of the training geometries fits the surrogates
(:func:`ringdamper.campaign.kriging.fit_campaign`); every usable point of the held-out geometries
(the validation split and the unused training geometries) is predicted with the plain ML variance
and with the leave-one-out calibrated one (:class:`~ringdamper.campaign.kriging.KrigingSurrogate`).
Coverage is the fraction with ``lower ≤ y ≤ upper``, the band of
:meth:`~ringdamper.campaign.kriging.KrigingSurrogate.predict` (ŷ ± 2σ for the identity transform, its
back-transform for the log; nominal 95.4 % for a calibrated Gaussian prediction), pooled over outputs,
on the validation split, and on the held-out points near the boundary (``1 − max_k |κ_k| < boundary``)
and inside; the band is widened by the round-off 1e-12 max|y| the fit takes as 0, as in the validation.
The campaign's ``min_training`` floor is lowered to the smallest size; an amplitude with
fewer usable points than that is left out.
"""
from __future__ import annotations

import numpy as np
import xarray as xr

from ringdamper.campaign.dataset import kappa as dataset_kappa
from ringdamper.campaign.exploration import BACKBONE_OUTPUTS
from ringdamper.campaign.kriging import BAND_PROBABILITY, CONSTANT_RTOL, KrigingSurrogate, fit_campaign
from ringdamper.io import variable

GROUPS = ("validation", "held_out", "near_boundary", "interior")


def covered(y: np.ndarray, lower: np.ndarray, upper: np.ndarray, atol: float = 0.0) -> np.ndarray:
    """``lower − atol ≤ y ≤ upper + atol`` per point (``atol``: the round-off the fit takes as 0)."""
    return (lower - atol <= y) & (y <= upper + atol)


def coverage_study(dataset: xr.Dataset, usable: xr.DataArray, sizes, settings: dict | None = None,
                   seed: int = 0, boundary: float = 0.2) -> xr.Dataset:
    """Coverage (size × calibration × group) of the held-out points, and the median calibration
    factor ψ per size; ``usable`` is the geometry × amplitude mask of usable points."""
    train_ids = np.flatnonzero((dataset.split == "training").values)
    sizes = [int(n) for n in sizes]
    if max(sizes) > train_ids.size or min(sizes) < 2:
        raise ValueError(f"training sizes {sizes} must lie in [2, {train_ids.size}]")
    # the study fits on fewer points than the campaign allows: lower its floor to the smallest size
    settings = {**(settings or {})}
    settings["min_training"] = min(settings.get("min_training", min(sizes)), min(sizes))
    rng = np.random.default_rng(seed)
    cover = np.full((len(sizes), 2, len(GROUPS)), np.nan)
    counts = np.zeros((len(sizes), len(GROUPS)), int)
    factor = np.full(len(sizes), np.nan)
    for i, n in enumerate(sizes):
        chosen = np.sort(rng.choice(train_ids, n, replace=False))
        held = np.setdiff1d(np.arange(dataset.sizes["geometry"]), chosen)
        fit = fit_campaign(dataset.isel(geometry=chosen), mask=usable.isel(geometry=chosen),
                           settings=settings)
        factor[i] = np.nanmedian(np.concatenate([fit[f"{o}_variance_factor"].values
                                                 for o in BACKBONE_OUTPUTS]))
        part = dataset.isel(geometry=held)
        X = dataset_kappa(part)
        ok = usable.isel(geometry=held).transpose("geometry", "amplitude").values
        margin = 1.0 - np.max(np.abs(X), axis=1)
        where = {"validation": (part.split == "validation").values, "held_out": np.ones(len(X), bool),
                 "near_boundary": margin < boundary, "interior": margin >= boundary}
        for j, calibrated in enumerate((False, True)):
            pred = KrigingSurrogate(fit, calibrated).predict(X, outputs=BACKBONE_OUTPUTS)
            hits = []
            for o in BACKBONE_OUTPUTS:
                y = part[o].transpose("geometry", "amplitude").values
                lower, upper = pred[f"{o}_lower"].values.T, pred[f"{o}_upper"].values.T
                fitted = ok & np.isfinite(lower) & np.isfinite(upper)      # unfitted models left out
                atol = CONSTANT_RTOL * float(np.nanmax(np.abs(fit[o].values)))
                hits.append(np.where(fitted, covered(y, lower, upper, atol), np.nan))
            hits = np.stack(hits)                                  # output, geometry, amplitude
            for k, g in enumerate(GROUPS):
                h = hits[:, where[g]]
                cover[i, j, k] = np.nanmean(h)
                counts[i, k] = int(np.sum(np.isfinite(h)))
    coords = {"n_training": variable("n_training", sizes, "1", "number of training geometries"),
              "calibration": variable("calibration", np.array(["ml", "jackknife"], dtype=object), "1",
                                      "predictive variance: ml (maximum likelihood) or jackknife "
                                      "(scaled on the normalised leave-one-out residuals)"),
              "group": variable("group", np.array(GROUPS, dtype=object), "1",
                                "held-out points: validation split, all held out, within the boundary "
                                "margin, inside it")}
    data = {"coverage": variable(("n_training", "calibration", "group"), cover, "1",
                                 f"fraction of held-out points within the {100 * BAND_PROBABILITY:g} % "
                                 "predictive band"),
            "n_points": variable(("n_training", "group"), counts, "1", "held-out point-output pairs"),
            "variance_factor": variable("n_training", factor, "1",
                                        "median leave-one-out variance factor psi over the models")}
    return xr.Dataset(data, coords=coords, attrs={"seed": seed, "boundary_margin": boundary,
                                                  "nominal": BAND_PROBABILITY})
