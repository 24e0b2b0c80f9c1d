"""Design-space exploration on the Kriging surrogates (paper §3.3): backbones of any geometry kappa,
their values at given response levels, envelopes over the 50^3 grid and the optimum.

Everything here goes through two functions:

* :func:`backbones` -- the Kriging prediction (median, 95.45 % band and its spread, in output units:
  :mod:`~ringdamper.campaign.kriging.surrogate`) of |q_res,z|, omega0, zeta, gamma at every modal
  amplitude alpha of the campaign, for many geometries at once: the predicted backbone of each geometry
  is the curve alpha -> (|q_res,z|, omega0, zeta, gamma) of the medians, which every envelope, optimum
  and Sobol index here reads (non-negative where the output is modelled on a log scale);
* :func:`at_levels` -- a backbone read at given values of one of its outputs (the response level
  |q_res,z| for the envelopes, the OAT maps and the Sobol indices; the forcing gamma for the
  resonant amplitude of the E-EBM at a forcing level).

Level interpolation: along the alpha grid the level variable x(alpha) is piecewise linear between
the grid nodes and so are the outputs; at level L the backbone is read on the segment
[alpha_j, alpha_j+1] whose x-range contains L. |q_res,z|(alpha) of a computed backbone is increasing,
but a Kriging prediction built amplitude by amplitude need not be: where x(alpha) is not monotone
several segments may contain L, and the rule is explicit -- ``crossing="first"`` takes the lowest
alpha (the first time the backbone reaches the level), ``"last"`` the highest (for a forcing level:
the largest amplitude balancing it, the conservative resonance). Levels the backbone never reaches
are NaN. :func:`monotone` tells which curves are monotone so callers can report the others.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import xarray as xr
from scipy.optimize import minimize

from ..io import variable
from .summary import grid_zeta_max

BACKBONE_OUTPUTS = ("q_res_z", "omega0", "zeta", "gamma")


@dataclass
class Backbones:
    """Predicted backbones: ``mean[name]`` (the median), ``std[name]`` (the band's spread, (upper -
    lower) / 4), ``lower[name]`` and ``upper[name]`` (the 95.45 % band) are (amplitude, point) arrays."""

    amplitude: np.ndarray
    mean: dict
    std: dict | None
    lower: dict | None = None
    upper: dict | None = None


def backbones(surrogate, X, outputs=BACKBONE_OUTPUTS, with_std: bool = True) -> Backbones:
    """Kriging backbones of the geometries ``X`` (point, 3) from a fitted
    :class:`~ringdamper.campaign.kriging.KrigingSurrogate` (built once from kriging.nc)."""
    pred = surrogate.predict(np.atleast_2d(np.asarray(X, dtype=float)), outputs=list(outputs), with_std=with_std)
    mean = {name: pred[name].values for name in outputs}
    if not with_std:
        return Backbones(amplitude=pred.amplitude.values, mean=mean, std=None)
    std, lower, upper = ({name: pred[f"{name}_{k}"].values for name in outputs} for k in ("std", "lower", "upper"))
    return Backbones(amplitude=pred.amplitude.values, mean=mean, std=std, lower=lower, upper=upper)


def monotone(x: np.ndarray) -> np.ndarray:
    """(point,) True where x (amplitude, point) increases strictly along the amplitude axis."""
    return np.all(np.diff(x, axis=0) > 0, axis=0)


def at_levels(x: np.ndarray, y: np.ndarray, levels, crossing: str = "first") -> np.ndarray:
    """Values of ``y`` (..., amplitude, point) where ``x`` (amplitude, point) equals each of
    ``levels`` (level,): array (..., level, point), NaN where a curve never reaches a level.
    Piecewise-linear interpolation in x on the segment chosen by ``crossing`` (module docstring)."""
    if crossing not in ("first", "last"):
        raise ValueError(f"crossing = {crossing!r}: choose 'first' or 'last'")
    x, y = np.asarray(x, float), np.asarray(y, float)
    levels = np.atleast_1d(np.asarray(levels, float))
    x0, x1 = x[:-1], x[1:]
    lo, hi = np.minimum(x0, x1), np.maximum(x0, x1)
    n_seg = x0.shape[0]
    out = np.empty(y.shape[:-2] + (levels.size, x.shape[-1]))  # every level is written below
    for k, level in enumerate(levels):
        hit = (lo <= level) & (level <= hi)
        reached = hit.any(axis=0)
        j = hit.argmax(axis=0) if crossing == "first" else n_seg - 1 - hit[::-1].argmax(axis=0)
        xa = np.take_along_axis(x0, j[None], 0)[0]
        xb = np.take_along_axis(x1, j[None], 0)[0]
        span = xb - xa
        t = np.divide(level - xa, span, out=np.zeros_like(span), where=span != 0)
        idx = np.broadcast_to(j, y.shape[:-2] + (1, j.size))
        ya = np.take_along_axis(y[..., :-1, :], idx, -2)[..., 0, :]
        yb = np.take_along_axis(y[..., 1:, :], idx, -2)[..., 0, :]
        out[..., k, :] = np.where(reached, ya + t * (yb - ya), np.nan)
    return out


def cube_grid(n: int, box=((-1.0, 1.0),) * 3) -> np.ndarray:
    """(n^3, 3) full-factorial grid of ``n`` points per axis on ``box`` (kappa1 varies slowest)."""
    axes = [np.linspace(lo, hi, n) for lo, hi in box]
    return np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)


def one_at_a_time(i: int, n: int) -> np.ndarray:
    """(n, 3) geometries with kappa_i on [-1, 1] and the other two at 0 (paper Figs. 14-16)."""
    X = np.zeros((n, 3))
    X[:, i] = np.linspace(-1.0, 1.0, n)
    return X


def predicted_zeta_max(bb: Backbones, q_max: float = np.inf) -> tuple[np.ndarray, np.ndarray]:
    """:func:`~ringdamper.campaign.summary.grid_zeta_max` of the Kriging-predicted (median) backbones:
    the largest predicted ζ over the α nodes where the predicted |q_res,z| <= ``q_max``, and the
    amplitude index where it is reached ((point,) arrays). A prediction has no status, so every
    node counts, and the maximum of a piecewise-linear backbone lies on a node."""
    return grid_zeta_max(bb.mean["q_res_z"], bb.mean["zeta"], q_max)


def resonant_amplitude(bb: Backbones, gamma: float) -> np.ndarray:
    """(point,) E-EBM resonant amplitude |q_res,z| at forcing level ``gamma`` (N): the backbone read
    where gamma(alpha) = gamma, the largest balancing amplitude if several (NaN if never reached)."""
    return at_levels(bb.mean["gamma"], bb.mean["q_res_z"], [gamma], crossing="last")[0]


@dataclass
class GridExploration:
    """Result of :func:`explore_grid`: envelopes (output -> (level,) min and max) on the common
    |q_res,z| axis ``levels``, and per grid point zeta_max (up to the optimum's response level, and
    over the whole backbone) and the resonant amplitude at the forcing level; ``n_non_monotone``
    counts the predicted |q_res,z|(alpha) curves that are not increasing."""

    X: np.ndarray
    levels: np.ndarray
    lower: dict
    upper: dict
    zeta_max: np.ndarray
    zeta_max_full: np.ndarray
    q_at_forcing: np.ndarray
    n_non_monotone: int


ENVELOPE_OUTPUTS = ("omega0", "zeta", "gamma")


def explore_grid(surrogate, X, levels, forcing: float, q_max: float = np.inf,
                 chunk: int = 20000) -> GridExploration:
    """Predict the backbones of the geometries ``X`` chunk by chunk; keep the envelopes of omega0,
    zeta, gamma against |q_res,z| on ``levels`` (paper Fig. 17), zeta_max (for |q_res,z| <= ``q_max``
    and over the whole backbone) and the resonant amplitude at ``forcing`` of every geometry."""
    lower = {k: np.full(len(levels), np.inf) for k in ENVELOPE_OUTPUTS}
    upper = {k: np.full(len(levels), -np.inf) for k in ENVELOPE_OUTPUTS}
    zmax, zfull, q_f, n_bad = np.empty(len(X)), np.empty(len(X)), np.empty(len(X)), 0
    for s in range(0, len(X), chunk):
        bb = backbones(surrogate, X[s:s + chunk], with_std=False)
        q = bb.mean["q_res_z"]
        n_bad += int((~monotone(q)).sum())
        values = at_levels(q, np.stack([bb.mean[k] for k in ENVELOPE_OUTPUTS]), levels)
        for k, name in enumerate(ENVELOPE_OUTPUTS):
            lower[name] = np.fmin(lower[name], np.nanmin(values[k], axis=-1, initial=np.inf))
            upper[name] = np.fmax(upper[name], np.nanmax(values[k], axis=-1, initial=-np.inf))
        zmax[s:s + chunk] = predicted_zeta_max(bb, q_max)[0]
        zfull[s:s + chunk] = predicted_zeta_max(bb)[0]
        q_f[s:s + chunk] = resonant_amplitude(bb, forcing)
    for name in ENVELOPE_OUTPUTS:
        lower[name][~np.isfinite(lower[name])] = np.nan
        upper[name][~np.isfinite(upper[name])] = np.nan
    return GridExploration(X=X, levels=np.asarray(levels), lower=lower, upper=upper, zeta_max=zmax,
                           zeta_max_full=zfull, q_at_forcing=q_f, n_non_monotone=n_bad)


def polish(objective, x0, h: float, box=((-1.0, 1.0),) * 3) -> tuple[np.ndarray, float]:
    """Bounded Nelder-Mead minimisation of ``objective(kappa)`` from the grid node ``x0`` with a start
    simplex of the grid step ``h``; returns (kappa, value), never worse than ``x0``."""
    lo, hi = np.array(box).T
    steps = np.where(x0 + h <= hi, h, -h)
    simplex = np.vstack([x0] + [x0 + np.eye(3)[k] * steps[k] for k in range(3)])
    res = minimize(objective, x0, method="Nelder-Mead", bounds=list(zip(lo, hi)),
                   options={"xatol": 1e-4, "fatol": 1e-10, "initial_simplex": simplex})
    f0 = float(objective(x0))
    return (np.clip(res.x, lo, hi), float(res.fun)) if res.fun < f0 else (np.asarray(x0), f0)


def summary(surrogate, kappa, forcing: float, q_max: float = np.inf) -> dict:
    """Predicted design figures of geometry ``kappa`` (flat, SI): zeta_max for |q_res,z| <= ``q_max``
    (median, with the spread and the 95.45 % band there) and the backbone point where it is reached
    (flagged if at the last amplitude: the true maximum may lie beyond the grid), the linearised
    (smallest-amplitude) omega0 and the resonant amplitude at ``forcing``."""
    bb = backbones(surrogate, np.asarray(kappa, float)[None])
    j = int(predicted_zeta_max(bb, q_max)[1][0])
    out = {"zeta_max": float(bb.mean["zeta"][j, 0]), "zeta_max_std": float(bb.std["zeta"][j, 0]),
           "zeta_max_lower": float(bb.lower["zeta"][j, 0]), "zeta_max_upper": float(bb.upper["zeta"][j, 0]),
           "zeta_max_at_last_amplitude": j == bb.amplitude.size - 1,
           "amplitude_at_zeta_max": float(bb.amplitude[j])}
    for name in ("q_res_z", "omega0", "gamma"):
        out[f"{name}_at_zeta_max"] = float(bb.mean[name][j, 0])
        out[f"{name}_at_zeta_max_std"] = float(bb.std[name][j, 0])
    out["omega0_stuck"] = float(bb.mean["omega0"][0, 0])
    out["q_res_z_at_forcing"] = float(resonant_amplitude(bb, forcing)[0])
    return out


def find_optimum(surrogate, grid: GridExploration, forcing: float, n_grid: int, q_max: float = np.inf) -> dict:
    """The optima of the explored grid, each polished off its best node (:func:`polish`): maximum
    zeta_max up to |q_res,z| = ``q_max`` (the criterion), maximum zeta_max over the whole backbone (for
    the record) and minimum resonant amplitude at ``forcing``."""
    h = 2.0 / (n_grid - 1)

    def neg_zeta_max(k, limit=q_max):
        return -predicted_zeta_max(backbones(surrogate, k[None], ("q_res_z", "zeta"), with_std=False), limit)[0][0]

    def q_forced(k):
        q = resonant_amplitude(backbones(surrogate, k[None], ("q_res_z", "gamma"), with_std=False), forcing)[0]
        return q if np.isfinite(q) else np.inf

    i = int(np.argmax(grid.zeta_max))
    k_zeta, _ = polish(neg_zeta_max, grid.X[i], h)
    i_full = int(np.argmax(grid.zeta_max_full))
    k_full, _ = polish(lambda k: neg_zeta_max(k, np.inf), grid.X[i_full], h)
    i_q = int(np.nanargmin(np.where(np.isfinite(grid.q_at_forcing), grid.q_at_forcing, np.inf)))
    k_q, q_min = polish(q_forced, grid.X[i_q], h)
    return {"kappa": k_zeta, "grid_kappa": grid.X[i], "grid_zeta_max": float(grid.zeta_max[i]),
            "kappa_full": k_full,
            "kappa_min_q": k_q, "grid_kappa_min_q": grid.X[i_q], "q_min": q_min}


def level_function(surrogate, levels, outputs=ENVELOPE_OUTPUTS):
    """f(X (n, 3)) -> (n, len(outputs) * len(levels)) array: the predicted backbone of each geometry
    read at the |q_res,z| ``levels`` (column o * len(levels) + l for output o, level l); the model
    of the Sobol studies. A level some geometry never reaches raises ValueError naming it."""
    levels = np.asarray(levels, dtype=float)

    def f(X):
        bb = backbones(surrogate, X, ("q_res_z",) + tuple(outputs), with_std=False)
        q = bb.mean["q_res_z"]
        values = at_levels(q, np.stack([bb.mean[k] for k in outputs]), levels)
        missed = np.isnan(values).any(axis=(0, 2))
        if missed.any():
            raise ValueError(
                f"|q_res,z| level(s) {levels[missed].tolist()} m not reached by the predicted backbone of "
                f"{int(np.isnan(values[0]).any(axis=0).sum())} of {len(X)} geometries (predicted |q_res,z| "
                f"spans {np.nanmin(q):.3g} ... {np.nanmin(q[-1]):.3g} m at the extreme amplitudes): lower "
                "sensitivity.levels or raise dnnm.amplitude_max")
        return values.reshape(-1, len(X)).T

    return f


def response_axis(dataset, mask, n: int) -> np.ndarray:
    """Common |q_res,z| axis (m): ``n`` points spanning the usable computed training backbones."""
    q = dataset.q_res_z.where(mask & (dataset.split == "training")).values
    return np.linspace(np.nanmin(q), np.nanmax(q), n)


def sweeps(surrogate, n: int, levels) -> xr.Dataset:
    """oat.nc: the predicted backbones (median, spread, band) of the one-at-a-time sweeps [kappa_i, others 0],
    kappa_i on n values of [-1, 1], and omega0, zeta, gamma read at the |q_res,z| ``levels``."""
    data = {}
    kinds = {"mean": "Kriging median of", "std": "Kriging predictive spread ((upper - lower) / 4) of",
             "lower": "lower bound of the 95.45 % Kriging band of",
             "upper": "upper bound of the 95.45 % Kriging band of"}
    per = {f"{name}_{kind}": [] for name in BACKBONE_OUTPUTS for kind in kinds}
    at = {name: [] for name in ENVELOPE_OUTPUTS}
    for i in range(3):
        bb = backbones(surrogate, one_at_a_time(i, n))
        for name in BACKBONE_OUTPUTS:
            for kind in kinds:
                per[f"{name}_{kind}"].append(getattr(bb, kind)[name].T)
        values = at_levels(bb.mean["q_res_z"], np.stack([bb.mean[k] for k in ENVELOPE_OUTPUTS]), levels)
        for k, name in enumerate(ENVELOPE_OUTPUTS):
            at[name].append(values[k].T)
    dims = ("parameter", "sample", "amplitude")
    for name in BACKBONE_OUTPUTS:
        for kind, words in kinds.items():
            data[f"{name}_{kind}"] = variable(dims, per[f"{name}_{kind}"], surrogate.units[name], f"{words} {name}")
    for name in ENVELOPE_OUTPUTS:
        data[f"{name}_at_level"] = variable(("parameter", "sample", "level"), at[name], surrogate.units[name],
                                            f"Kriging median of {name} at |q_res,z| (NaN: not reached)")
    coords = {"parameter": variable("parameter", np.array(["kappa1", "kappa2", "kappa3"], dtype=object), "1",
                                    "swept shape parameter (the other two are 0)"),
              "value": variable("sample", np.linspace(-1.0, 1.0, n), "1", "value of the swept parameter"),
              "amplitude": variable("amplitude", bb.amplitude, "kg0.5 m", "modal amplitude alpha"),
              "level": variable("level", np.asarray(levels), "m", "response level |q_res,z|")}
    return xr.Dataset(data, coords=coords)


def grid_dataset(surrogate, grid: GridExploration, optimum: dict, n_grid: int) -> xr.Dataset:
    """grid.nc: envelopes of Fig. 17, the predicted default and optimum backbones on the same
    |q_res,z| axis, and zeta_max and the resonant amplitude at the forcing level over the grid."""
    special = backbones(surrogate, np.vstack([np.zeros(3), optimum["kappa"]]), with_std=False)
    at = at_levels(special.mean["q_res_z"], np.stack([special.mean[k] for k in ENVELOPE_OUTPUTS]), grid.levels)
    data = {}
    for k, name in enumerate(ENVELOPE_OUTPUTS):
        u = surrogate.units[name]
        data[f"{name}_lower"] = variable("level", grid.lower[name], u, f"smallest predicted {name} over the grid")
        data[f"{name}_upper"] = variable("level", grid.upper[name], u, f"largest predicted {name} over the grid")
        data[f"{name}_default"] = variable("level", at[k, :, 0], u, f"predicted {name} of the default ring")
        data[f"{name}_optimum"] = variable("level", at[k, :, 1], u, f"predicted {name} of the optimum")
    cube = ("k1", "k2", "k3")
    data["zeta_max"] = variable(cube, grid.zeta_max.reshape((n_grid,) * 3), "1",
                                "maximum of the predicted damping ratio along the backbone up to "
                                "exploration.optimum_max_level")
    data["zeta_max_whole_backbone"] = variable(cube, grid.zeta_max_full.reshape((n_grid,) * 3), "1",
                                               "maximum of the predicted damping ratio along the whole backbone")
    data["q_res_z_at_forcing"] = variable(cube, grid.q_at_forcing.reshape((n_grid,) * 3), "m",
                                          "predicted E-EBM resonant amplitude at the forcing level")
    axis = np.linspace(-1.0, 1.0, n_grid)
    coords = {"level": variable("level", grid.levels, "m", "response level |q_res,z|"),
              **{c: variable(c, axis, "1", f"grid value of kappa{i + 1}") for i, c in enumerate(cube)}}
    attrs = {"optimum_kappa": np.asarray(optimum["kappa"], float), "n_geometries": len(grid.X),
             "n_non_monotone": grid.n_non_monotone}
    return xr.Dataset(data, coords=coords, attrs=attrs)


def forcing_of(surrogate, kappa, level: float) -> float:
    """Forcing gamma (N) at which the predicted backbone of ``kappa`` reaches |q_res,z| = ``level``."""
    bb = backbones(surrogate, np.asarray(kappa, float)[None], ("q_res_z", "gamma"), with_std=False)
    gamma = float(at_levels(bb.mean["q_res_z"], bb.mean["gamma"], [level])[0, 0])
    if not np.isfinite(gamma):
        raise ValueError(f"exploration.reference_amplitude = {level} m is not reached by the predicted "
                         f"backbone of kappa = {list(kappa)} (|q_res,z| up to {bb.mean['q_res_z'].max():.3g} m)")
    return gamma


def criterion(q_max: float) -> str:
    """The optimum's criterion in words (docs/analytics.md says why)."""
    return (f"maximum over the design space of zeta_max(kappa), the largest Kriging-predicted modal damping "
            f"ratio (median) along the geometry's backbone up to |q_res,z| = {q_max:g} m "
            "(exploration.optimum_max_level), "
            "the paper's criterion (§3.3.2) on the response range of interest; best node of the grid, "
            "polished by bounded Nelder-Mead")


def _floats(a) -> list:
    return [round(float(v), 6) for v in a]


def optimum_record(surrogate, grid: GridExploration, optimum: dict, forcing: float, cfg: dict) -> dict:
    """Content of optimum.yaml: the optimum kappa, the criterion, the predicted figures there and at
    the default ring, and the second view (minimum resonant amplitude at a forcing level)."""
    q_max = cfg["optimum_max_level"]
    at_opt = summary(surrogate, optimum["kappa"], forcing, q_max)
    at_default = summary(surrogate, np.zeros(3), forcing, q_max)
    at_q_opt = summary(surrogate, optimum["kappa_min_q"], forcing, q_max)
    at_full = summary(surrogate, optimum["kappa_full"], forcing)
    return {
        "kappa": _floats(optimum["kappa"]),
        "criterion": criterion(q_max),
        "predicted": at_opt,
        "default_predicted": at_default,
        "whole_backbone": {"kappa": _floats(optimum["kappa_full"]), "zeta_max": at_full["zeta_max"],
                           "zeta_max_std": at_full["zeta_max_std"],
                           "q_res_z_at_zeta_max": at_full["q_res_z_at_zeta_max"],
                           "zeta_max_at_last_amplitude": at_full["zeta_max_at_last_amplitude"]},
        "grid": {"points_per_axis": int(cfg["grid_points"]), "best_node": _floats(optimum["grid_kappa"]),
                 "best_node_zeta_max": float(optimum["grid_zeta_max"]),
                 "non_monotone_backbones": int(grid.n_non_monotone)},
        "forcing_view": {
            "criterion": ("minimum predicted E-EBM resonant amplitude |q_res,z| at the forcing level that "
                          f"drives the default ring to {cfg['reference_amplitude']} m (the Table 3 view)"),
            "forcing_level": float(forcing),
            "kappa": _floats(optimum["kappa_min_q"]),
            "q_res_z": float(optimum["q_min"]),
            "zeta_max": at_q_opt["zeta_max"],
            "q_res_z_of_zeta_optimum": at_opt["q_res_z_at_forcing"],
            "q_res_z_default": at_default["q_res_z_at_forcing"],
        },
    }
