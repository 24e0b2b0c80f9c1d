"""Ordinary Kriging surrogates of the dNNM outputs, one per (output, modal amplitude) (paper §3.2).

Model (paper Eq. 7): y(x) = β + Z(x), x = κ ∈ [-1, 1]³, Z a centred stationary Gaussian process of
covariance σ² (ρ_θ(x - x') + ν δ_{x,x'}), with an anisotropic correlation ρ_θ of the scaled distance
d = ‖(x - x') / θ‖ (θ one scale per parameter):

- ``matern52`` (default):          ρ = (1 + √5 d + 5 d²/3) exp(-√5 d)
- ``squared_exponential``:        ρ = exp(-d²/2)

(both exactly OpenTURNS' ``MaternModel(ν=5/2)`` / ``SquaredExponential``), and ν a nugget factor.

Fit (OpenTURNS ``GaussianProcessFitter``, constant basis, maximum likelihood): for given θ and ν,
β̂ = (1ᵀR⁻¹y)/(1ᵀR⁻¹1) (generalised least squares) and σ̂² = (y - β̂1)ᵀR⁻¹(y - β̂1)/(N - 1) (OpenTURNS'
unbiased analytical amplitude), R = [ρ_θ(xᵢ - xⱼ)] + νI; θ maximises the reduced log-likelihood
-½ (log det(σ̂² R) + N - 1) - N log √(2π), by Cobyla from ``n_starts`` starting points (a seeded
log-uniform Latin hypercube over the bounds, OpenTURNS ``MultiStart``). ν is fixed (default 1e-12,
OpenTURNS' own round-off floor) or, given as [low, high], profiled over NUGGET_PROFILE log-spaced values.

Scale bounds are tied to the width w = 2 of the κ domain: θ_k ∈ scale_bounds × w, default
[0.05, 5] × 2 = [0.1, 10]. Below 0.1 the correlation between neighbouring training points (spacing
≈ 0.4 for 100 points in 3-D) vanishes and the model degenerates into spikes. Above ~10 the likelihood of
a smooth response keeps rising along a flat ridge (θ, σ → ∞ together) while R becomes ill-conditioned:
on the test function of tests/campaign/test_kriging.py (100 LHS points, Matérn 5/2), θ ≤ 10 gives
cond(R) ≈ 6e8 and 2σ coverage 0.999 at R² = 0.9997, θ ≤ 40 gives cond(R) ≈ 4e10, coverage 0.64 and
interpolation errors of 1e-6 from round-off, for no gain in R². The squared-exponential kernel is
worse conditioned still (cond(R) ≈ 1e13 on the same data); give it a nugget (~1e-8) if used.

Predictor (paper Eq. 8) and ordinary-Kriging variance, with r₀ = [ρ_θ(x₀ - xᵢ)] (no nugget):

    ŷ(x₀)  = β + r₀ᵀ R⁻¹ (y - β1)
    s²(x₀) = σ² (1 + ν - r₀ᵀR⁻¹r₀ + (1 - 1ᵀR⁻¹r₀)² / (1ᵀR⁻¹1))

The last term accounts for the estimation of β; this is exactly what OpenTURNS'
``GaussianProcessRegression`` / ``GaussianProcessConditionalCovariance`` compute at any input that does
not coincide with a training input (there OpenTURNS also adds σ²ν to the cross-covariance, so its mean
jumps to the noisy observation; ours stays continuous). Predictions are made here in numpy from the
stored hyperparameters (``kriging.nc`` alone, no refit): R is factorised once per model at load.

Leave-one-out with fixed θ, σ, ν (Dubrule 1983, "Cross validation of kriging in a unique
neighborhood", Math. Geol. 15: 687–699): with the ordinary-Kriging system K = [[R, 1], [1ᵀ, 0]],

    eᵢ = yᵢ - ŷ₋ᵢ(xᵢ) = [K⁻¹ (y; 0)]ᵢ / [K⁻¹]ᵢᵢ = [R⁻¹(y - β̂1)]ᵢ / [R⁻¹ - R⁻¹11ᵀR⁻¹/(1ᵀR⁻¹1)]ᵢᵢ,

where ŷ₋ᵢ re-estimates β on the other N - 1 points; Q² = 1 - Σeᵢ² / Σ(yᵢ - ȳ)². The leave-one-out
predictive variance is s²₋ᵢ = σ² / [K⁻¹]ᵢᵢ (same reference).

Variance calibration. The ML amplitude σ̂² makes the standardised *training* residuals have unit
variance under the model; with few points, estimated θ and a misspecified correlation the
predictive σ is then too small away from the data, and the residuals are heavier-tailed than a
Gaussian: the ±2σ band covered 85–93 % of the campaign's validation points per output (90 %
pooled) instead of 95.4 %. The predictive σ is therefore scaled so that the band holds the
nominal share of the normalised leave-one-out residuals tᵢ = |eᵢ| / s₋ᵢ (the jackknife with
normalised conformity scores: Barber, Candès, Ramdas & Tibshirani 2021, "Predictive inference with
the jackknife+", Ann. Stat. 49: 486–507; Lei, G'Sell, Rinaldo, Tibshirani & Wasserman 2018,
"Distribution-free predictive inference for regression", JASA 113: 1094–1111, §5.2):

    q = t₍ₖ₎,  k = ⌈(N + 1) p⌉ (capped at N),  p = P(|Z| ≤ 2) = 0.9545,     s(x₀) ← (q / 2) s(x₀),

stored per model as the variance factor ψ = (q/2)² (ψ = 1 reproduces the ML variance). The rate is
empirical, not guaranteed (the jackknife's guarantee is 1 − 2(1 − p)); docs/method_limits.md §3
charts the coverage before and after against the training size and near the boundary.

References: Sacks, Welch, Mitchell & Wynn (1989) Stat. Sci. 4: 409–423; Jones, Schonlau & Welch (1998)
J. Glob. Optim. 13: 455–492; Rasmussen & Williams (2006) Gaussian Processes for Machine Learning §2.7.
"""

from __future__ import annotations

import logging
from concurrent.futures import ProcessPoolExecutor

import numpy as np
import scipy.linalg as sla
from scipy.linalg import blas
import xarray as xr

from ..io import variable

log = logging.getLogger(__name__)

OUTPUTS = ("q_res_z", "omega0", "zeta", "gamma")
PARAMETERS = ("kappa1", "kappa2", "kappa3")
DOMAIN_WIDTH = 2.0  # κ ∈ [-1, 1]
KERNELS = ("matern52", "squared_exponential")
DEFAULT_SETTINGS = {
    "kernel": "matern52",        # correlation function, one of KERNELS
    "n_starts": 8,               # multistart size of the likelihood maximisation
    "seed": 0,                   # seed of the starting points (OpenTURNS RandomGenerator)
    "scale_bounds": (0.05, 5.0),  # θ bounds as multiples of the κ-domain width (2)
    "nugget": 1.0e-12,           # fixed nugget factor ν ≥ 0, or [low, high] to estimate it by ML
    "min_training": 10,          # fewer usable points than this: the model is not fitted (status 2)
}
STATUS_GP, STATUS_CONSTANT, STATUS_UNFITTED = 0, 1, 2
STATUS_MEANINGS = "gaussian_process constant_data too_few_training_points"
MATCH_RTOL = 1.0e-6  # allowed numpy/OpenTURNS prediction gap, fraction of the data spread
AMPLITUDE_RTOL = 1.0e-6  # OpenTURNS' amplitude vs the closed-form ML estimate at its θ, ν
NUGGET_PROFILE = 5  # log-spaced nugget values tried when the nugget is estimated
SIGMA_BAND = 2.0  # the predictive band ±2σ ...
BAND_PROBABILITY = 0.9545  # ... and its nominal coverage P(|Z| <= 2) for a Gaussian prediction
# data whose spread is below this times max|y| (round-off) are taken as constant: no process is fitted
CONSTANT_RTOL = 1.0e-12


def check_settings(settings: dict | None) -> dict:
    """Settings with defaults filled in; a clear error naming the ``surrogate.<key>`` otherwise."""
    s = {**DEFAULT_SETTINGS, **(settings or {})}
    unknown = sorted(set(s) - set(DEFAULT_SETTINGS))
    if unknown:
        raise ValueError(f"surrogate: unknown keys {unknown}; allowed {sorted(DEFAULT_SETTINGS)}")
    if s["kernel"] not in KERNELS:
        raise ValueError(f"surrogate.kernel = {s['kernel']!r}; allowed {KERNELS}")
    for key, low in (("n_starts", 1), ("seed", 0), ("min_training", 2)):
        if not isinstance(s[key], (int, np.integer)) or s[key] < low:
            raise ValueError(f"surrogate.{key} = {s[key]!r}; must be an integer >= {low}")
    lo_hi = np.asarray(s["scale_bounds"], dtype=float)
    if lo_hi.shape != (2,) or not (0.0 < lo_hi[0] < lo_hi[1] < np.inf):
        raise ValueError(f"surrogate.scale_bounds = {s['scale_bounds']!r}; must be [low, high] with 0 < low < high")
    nugget = np.asarray(s["nugget"], dtype=float)
    if nugget.shape == ():
        if not 0.0 <= nugget < 1.0:
            raise ValueError(f"surrogate.nugget = {s['nugget']!r}; a fixed nugget must be in [0, 1)")
    elif nugget.shape != (2,) or not (0.0 < nugget[0] < nugget[1] < 1.0):
        raise ValueError(f"surrogate.nugget = {s['nugget']!r}; an estimated nugget needs [low, high], 0 < low < high < 1")
    return {**s, "scale_bounds": tuple(lo_hi), "nugget": float(nugget) if nugget.shape == () else tuple(nugget)}


def correlation(kernel: str, d2: np.ndarray) -> np.ndarray:
    """ρ of the squared scaled distance d² (``d2`` is overwritten)."""
    if kernel == "matern52":
        d2 *= 5.0
        s = np.sqrt(d2, out=d2)
        poly = s * s
        poly *= 1.0 / 3.0
        poly += s
        poly += 1.0
        np.negative(s, out=s)
        poly *= np.exp(s, out=s)
        return poly
    if kernel == "squared_exponential":
        d2 *= -0.5
        return np.exp(d2, out=d2)
    raise ValueError(f"kernel {kernel!r}; allowed {KERNELS}")


def _squared_differences(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """(d, len(a), len(b)) squared coordinate differences, shared by every model on the same points."""
    return (a.T[:, :, None] - b.T[:, None, :]) ** 2


def _scaled_d2(sq: np.ndarray, scale: np.ndarray) -> np.ndarray:
    return np.tensordot(1.0 / scale**2, sq, axes=1)


class GPModel:
    """One ordinary-Kriging model in numpy form: R factorised once, then vectorised prediction and LOO.

    ``sigma == 0`` is the constant model (degenerate data): ŷ = β, s = 0. ``variance_factor`` ψ scales
    the predictive variance (module doc, *variance calibration*; 1: the ML variance).
    """

    def __init__(self, kernel, scale, sigma, nugget, beta, x, y, variance_factor: float = 1.0):
        self.kernel, self.scale = kernel, np.asarray(scale, dtype=float)
        self.variance_factor = float(variance_factor)
        self.sigma, self.nugget, self.beta = float(sigma), float(nugget), float(beta)
        self.x, self.y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
        if self.sigma > 0.0:
            R = correlation(kernel, _scaled_d2(_squared_differences(self.x, self.x), self.scale))
            R[np.diag_indices_from(R)] += self.nugget
            try:
                cho = sla.cho_factor(R, lower=True)
            except np.linalg.LinAlgError as err:
                raise np.linalg.LinAlgError(f"correlation matrix not positive definite (scale {self.scale}, "
                                            f"nugget {self.nugget}): {err}") from None
            # R = L Lᵀ; L⁻¹ (lower triangular) serves the variance: r₀ᵀR⁻¹r₀ = ‖L⁻¹r₀‖²
            self.Linv = sla.solve_triangular(np.tril(cho[0]), np.eye(len(self.y)), lower=True)
            self.Linv_1 = self.Linv.sum(axis=1)
            self.Rinv_1 = sla.cho_solve(cho, np.ones(len(self.y)))
            self.one_Rinv_1 = self.Rinv_1.sum()
            self.Rinv_y = sla.cho_solve(cho, self.y)
            self.alpha = self.Rinv_y - self.beta * self.Rinv_1

    @property
    def is_constant(self) -> bool:
        return self.sigma == 0.0

    def gls_beta(self) -> float:
        """β̂ = 1ᵀR⁻¹y / 1ᵀR⁻¹1, the generalised least-squares trend at the model's θ, ν."""
        return float(self.Rinv_1 @ self.y / self.one_Rinv_1) if not self.is_constant else float(np.mean(self.y))

    def predict(self, X: np.ndarray, with_std: bool = True, sq: np.ndarray | None = None):
        """Mean ŷ (m,) and standard deviation s (m,) or None at X (m, d) (Eq. 8 and the variance above).

        ``sq``: the precomputed squared differences between X and the training inputs, if shared."""
        m = len(X)
        if self.is_constant:
            return np.full(m, self.beta), (np.zeros(m) if with_std else None)
        if sq is None:
            sq = _squared_differences(np.asarray(X, dtype=float), self.x)
        r = correlation(self.kernel, _scaled_d2(sq, self.scale))
        mean = self.beta + r @ self.alpha
        if not with_std:
            return mean, None
        b = blas.dtrmm(1.0, self.Linv, r.T, lower=1)  # L⁻¹r₀ for every point, (N, m)
        u = 1.0 - self.Linv_1 @ b
        var = 1.0 + self.nugget - np.einsum("ij,ij->j", b, b) + u * u / self.one_Rinv_1
        return mean, self.sigma * np.sqrt(self.variance_factor * np.maximum(var, 0.0))

    def ml_sigma(self) -> float:
        """σ̂ = √((y − β̂1)ᵀR⁻¹(y − β̂1) / (N − 1)), the analytical maximum-likelihood amplitude at the
        model's θ, ν (OpenTURNS' unbiased estimate)."""
        if self.is_constant:
            return 0.0
        beta = self.gls_beta()
        w = self.Rinv_y - beta * self.Rinv_1
        return float(np.sqrt(max((self.y - beta) @ w, 0.0) / (len(self.y) - 1)))

    def loo_residuals(self) -> np.ndarray:
        """Analytic leave-one-out residuals eᵢ = yᵢ - ŷ₋ᵢ(xᵢ) (Dubrule 1983, formula in the module doc)."""
        if self.is_constant:
            return self.y - self.beta
        w, diag = self._loo_parts()
        return w / diag

    def _loo_parts(self):
        """``R⁻¹(y − β̂1)`` and ``[K⁻¹]ᵢᵢ`` of the ordinary-Kriging system (Dubrule 1983)."""
        w = self.Rinv_y - self.gls_beta() * self.Rinv_1
        diag = np.einsum("ij,ij->j", self.Linv, self.Linv) - self.Rinv_1**2 / self.one_Rinv_1
        return w, diag

    def loo_variance_factor(self) -> float:
        """ψ = (q/2)², q the ⌈(N+1)p⌉-th smallest normalised leave-one-out residual |eᵢ|/s₋ᵢ,
        s₋ᵢ = σ/√[K⁻¹]ᵢᵢ (module doc, *variance calibration*); 1 for the constant model."""
        if self.is_constant:
            return 1.0
        w, diag = self._loo_parts()
        t = np.sort(np.abs(w) / np.sqrt(diag) / self.sigma)
        k = min(int(np.ceil((t.size + 1) * BAND_PROBABILITY)), t.size)
        return float((t[k - 1] / SIGMA_BAND) ** 2)


def q2(y: np.ndarray, residuals: np.ndarray) -> float:
    """Q² = 1 - Σe² / Σ(y - ȳ)² (NaN for constant y)."""
    ss = np.sum((y - np.mean(y)) ** 2)
    return float(1.0 - np.sum(residuals**2) / ss) if ss > 0 else np.nan


def _ot_kernel(kernel: str, dim: int):
    import openturns as ot

    if kernel == "matern52":
        return ot.MaternModel([1.0] * dim, [1.0], 2.5)
    return ot.SquaredExponential([1.0] * dim, [1.0])


def _starting_points(lower: np.ndarray, upper: np.ndarray, n: int, seed: int):
    """Seeded log-uniform LHS over the bounds, in the coordinates the fitter's solver works in
    (OpenTURNS maps the bounds onto [0, 1] when ``GaussianProcessFitter-OptimizationNormalization``)."""
    import openturns as ot

    ot.RandomGenerator.SetSeed(int(seed))
    dist = ot.JointDistribution([ot.LogUniform(np.log(lo), np.log(hi)) for lo, hi in zip(lower, upper)])
    theta = np.array(ot.LHSExperiment(dist, int(n)).generate())
    if ot.ResourceMap.GetAsBool("GaussianProcessFitter-OptimizationNormalization"):
        theta = (theta - lower) / (upper - lower)
    return ot.Sample(theta)


def _fit_ot_fixed_nugget(x: np.ndarray, y: np.ndarray, s: dict, nugget: float):
    import openturns as ot

    dim = x.shape[1]
    cov = _ot_kernel(s["kernel"], dim)
    cov.setNuggetFactor(nugget)
    lower = np.full(dim, s["scale_bounds"][0] * DOMAIN_WIDTH)
    upper = np.full(dim, s["scale_bounds"][1] * DOMAIN_WIDTH)
    fitter = ot.GaussianProcessFitter(x, y[:, None], cov, ot.ConstantBasisFactory(dim).build())
    fitter.setOptimizationBounds(ot.Interval(lower, upper))
    solver = ot.Cobyla()
    solver.setCheckStatus(False)
    fitter.setOptimizationAlgorithm(ot.MultiStart(solver, _starting_points(lower, upper, s["n_starts"], s["seed"])))
    fitter.run()
    return fitter.getResult()


def fit_ot(x: np.ndarray, y: np.ndarray, settings: dict | None = None):
    """Maximum-likelihood ordinary Kriging with OpenTURNS: the ``GaussianProcessFitterResult``.

    An estimated nugget (``nugget: [low, high]``) is profiled: the fit is repeated at NUGGET_PROFILE
    log-spaced values and the one of largest likelihood kept (OpenTURNS' optimiser works on the
    parameters linearly scaled to [0, 1], where it cannot resolve a nugget spanning decades)."""
    s = check_settings(settings)
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    nuggets = np.geomspace(*s["nugget"], NUGGET_PROFILE) if isinstance(s["nugget"], tuple) else [s["nugget"]]
    results = [_fit_ot_fixed_nugget(x, y, s, float(nu)) for nu in nuggets]
    return max(results, key=lambda r: r.getOptimalLogLikelihood())


def _is_constant(y: np.ndarray) -> bool:
    return np.ptp(y) <= CONSTANT_RTOL * np.max(np.abs(y))


def fit_model(x: np.ndarray, y: np.ndarray, settings: dict | None = None, name: str = "y"):
    """Fit one model; returns (GPModel, reduced log-likelihood). Constant data (spread below
    CONSTANT_RTOL × max|y|, e.g. ζ ≡ 0) give the constant model β = mean(y), σ = 0 without OpenTURNS.
    Non-finite data raise ValueError naming ``name``."""
    s = check_settings(settings)
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    if x.ndim != 2 or y.shape != (len(x),):
        raise ValueError(f"{name}: inputs must be (n, d) and outputs (n,), got {x.shape} and {y.shape}")
    bad = ~np.isfinite(y) | ~np.all(np.isfinite(x), axis=1)
    if bad.any():
        raise ValueError(f"{name}: {bad.sum()} non-finite training value(s) at rows {np.flatnonzero(bad)[:10].tolist()}; "
                         "filter failed geometries (mask) before fitting")
    if len(y) < 2:
        raise ValueError(f"{name}: {len(y)} training point(s); at least 2 are needed")
    if _is_constant(y):
        return GPModel(s["kernel"], np.full(x.shape[1], np.nan), 0.0, 0.0, float(np.mean(y)), x, y), np.nan
    result = fit_ot(x, y, s)
    cm = result.getCovarianceModel()
    model = GPModel(s["kernel"], np.array(cm.getScale()), cm.getAmplitude()[0], cm.getNuggetFactor(),
                    result.getTrendCoefficients()[0], x, y)
    sigma = model.ml_sigma()
    if abs(sigma - model.sigma) > AMPLITUDE_RTOL * sigma:
        # OpenTURNS 1.27 occasionally returns its starting amplitude (1) instead of the analytical
        # estimate at the optimum θ (seen on one of 120 campaign models): the predictive σ was then
        # wrong by orders of magnitude. The ML amplitude at θ, ν is closed-form, so it is restored.
        log.warning("%s: OpenTURNS amplitude %.3g is not the ML estimate %.3g at its optimum; using the latter",
                    name, model.sigma, sigma)
        model = GPModel(s["kernel"], model.scale, sigma, model.nugget, model.beta, x, y)
    _check_against_ot(model, result, name)
    return model, float(result.getOptimalLogLikelihood())


def _check_against_ot(model: GPModel, fitter_result, name: str) -> None:
    """Warn when the numpy predictor departs from OpenTURNS' GaussianProcessRegression (at the midpoints
    of successive training points) by more than MATCH_RTOL of the data spread: R is then too
    ill-conditioned (OpenTURNS regularises its Cholesky factor silently); a nugget cures it."""
    import openturns as ot

    algo = ot.GaussianProcessRegression(fitter_result)
    algo.run()
    mid = 0.5 * (model.x[:-1] + model.x[1:])
    ours, _ = model.predict(mid, with_std=False)
    gap = np.max(np.abs(ours - np.asarray(algo.getResult().getMetaModel()(mid)).ravel())) / np.ptp(model.y)
    if gap > MATCH_RTOL:
        log.warning("%s: numpy and OpenTURNS predictions differ by %.2g of the data spread (ill-conditioned "
                    "correlation matrix, scale %s); consider a nugget", name, gap, np.round(model.scale, 3))


def _training_mask(dataset: xr.Dataset, mask) -> np.ndarray:
    shape = (dataset.sizes["geometry"], dataset.sizes["amplitude"])
    if mask is None:
        return np.ones(shape, dtype=bool)
    if isinstance(mask, xr.DataArray):
        mask = mask.transpose("geometry", *[d for d in ("amplitude",) if d in mask.dims]).values
    mask = np.asarray(mask, dtype=bool)
    if mask.shape == shape[:1]:
        mask = np.repeat(mask[:, None], shape[1], axis=1)
    if mask.shape != shape:
        raise ValueError(f"mask has shape {mask.shape}; expected (geometry,) = {shape[:1]} or (geometry, amplitude) = {shape}")
    return mask


def _check_inputs(dataset: xr.Dataset, outputs) -> np.ndarray:
    if not {"geometry", "amplitude"} <= set(dataset.dims):
        raise ValueError(f"dataset dims are {tuple(dataset.dims)}; expected (geometry, amplitude)")
    missing = [k for k in (*PARAMETERS, *outputs) if k not in dataset.variables]
    if missing:
        raise ValueError(f"dataset lacks {missing}; needs coords {PARAMETERS} and data vars {tuple(outputs)}")
    kappa = np.column_stack([dataset[k].values for k in PARAMETERS]).astype(float)
    if not np.all(np.isfinite(kappa)) or np.abs(kappa).max() > 1.0:
        raise ValueError("dataset kappa1..3 must be finite and within [-1, 1]")
    return kappa


def _fit_task(task):
    """:func:`fit_model` of one ``(x, y, settings, name)`` (a top-level function: process pools pickle it)."""
    return fit_model(*task)


def _fit_all(tasks: list, workers: int) -> list:
    """:func:`fit_model` of every task, in order, on ``workers`` processes (each fit is seeded by the
    settings alone, so the models do not depend on the number of workers)."""
    if workers <= 1 or len(tasks) < 2:
        return [_fit_task(t) for t in tasks]
    with ProcessPoolExecutor(max_workers=workers) as pool:
        return list(pool.map(_fit_task, tasks, chunksize=max(1, len(tasks) // (4 * workers))))


def fit_campaign(dataset: xr.Dataset, outputs=OUTPUTS, mask=None, settings: dict | None = None,
                 workers: int = 1) -> xr.Dataset:
    """One Kriging model per (output, amplitude) on the usable geometries → the ``kriging.nc`` Dataset.

    dataset: dims (geometry, amplitude), coords kappa1..3 (on geometry), data vars ``outputs``.
    mask: bool (geometry,) or (geometry, amplitude), True where a point may train (default all): the
        caller excludes validation geometries and failed solves; a NaN/inf output under the mask is an
        error naming the output and amplitude. Geometries never used are not stored.
    settings: the ``surrogate`` section; keys and defaults in DEFAULT_SETTINGS (see check_settings).
    workers: processes fitting the models side by side (the result does not depend on it).
    Layout of the result: docs/surrogate.md.
    """
    s = check_settings(settings)
    outputs = tuple(outputs)
    kappa = _check_inputs(dataset, outputs)
    use = _training_mask(dataset, mask)
    used = use.any(axis=1)  # geometries that train at least one model: the only ones stored
    dataset, kappa, use = dataset.isel(geometry=used), kappa[used], use[used]
    n_amp, n_out, dim = dataset.sizes["amplitude"], len(outputs), len(PARAMETERS)
    scale = np.full((n_out, n_amp, dim), np.nan)
    nugget, loglik, q2s = (np.full((n_out, n_amp), np.nan) for _ in range(3))
    status = np.full((n_out, n_amp), STATUS_UNFITTED, dtype=np.int8)
    n_train = use.sum(axis=0)
    values = {out: dataset[out].transpose("geometry", "amplitude").values.astype(float) for out in outputs}
    tasks, keys = [], []
    for out in outputs:
        for ia in range(n_amp):
            rows = np.flatnonzero(use[:, ia])
            amp = float(dataset["amplitude"].values[ia])
            if len(rows) < s["min_training"]:
                log.warning("%s at amplitude %.4g: %d usable geometries < surrogate.min_training = %d; not fitted",
                            out, amp, len(rows), s["min_training"])
                continue
            tasks.append((kappa[rows], values[out][rows, ia], s, f"{out} at amplitude[{ia}] = {amp:.6g}"))
            keys.append((out, ia, rows))
    fitted = {(out, ia): (rows, *fit) for (out, ia, rows), fit in zip(keys, _fit_all(tasks, workers))}
    per_output = {}
    for io, out in enumerate(outputs):
        beta, sigma, factor = np.full(n_amp, np.nan), np.full(n_amp, np.nan), np.full(n_amp, np.nan)
        loo = np.full((n_amp, len(kappa)), np.nan)
        train = np.where(use, values[out], np.nan).T
        for ia in range(n_amp):
            if (out, ia) not in fitted:
                continue
            rows, model, ll = fitted[out, ia]
            status[io, ia] = STATUS_CONSTANT if model.is_constant else STATUS_GP
            scale[io, ia], nugget[io, ia], loglik[io, ia] = model.scale, model.nugget, ll
            beta[ia], sigma[ia], factor[ia] = model.beta, model.sigma, model.loo_variance_factor()
            loo[ia, rows] = model.loo_residuals()
            q2s[io, ia] = q2(model.y, loo[ia, rows])
        units, long_name = dataset[out].attrs.get("units", "1"), dataset[out].attrs.get("long_name", out)
        per_output[out] = variable(("amplitude", "geometry"), train, units, f"training values of {long_name} (NaN: not used)")
        per_output[f"{out}_beta"] = variable("amplitude", beta, units, f"Kriging constant trend of {out}")
        per_output[f"{out}_sigma"] = variable("amplitude", sigma, units, f"Kriging process standard deviation of {out}")
        per_output[f"{out}_variance_factor"] = variable(
            "amplitude", factor, "1", f"leave-one-out calibration factor of the predictive variance of {out}")
        per_output[f"{out}_loo_residual"] = variable(("amplitude", "geometry"), loo, units,
                                                     f"leave-one-out residual of {out} (fixed hyperparameters)")
    amp_attrs = {"units": "1", "long_name": "modal amplitude", **dataset["amplitude"].attrs}
    geometry = dataset["geometry"].values if "geometry" in dataset.coords else np.arange(len(kappa))
    data = {
        "kappa": variable(("geometry", "parameter"), kappa, "1", "normalised shape parameters of the training geometries"),
        "training_mask": variable(("amplitude", "geometry"), use.T.astype(np.int8), "1",
                                  "1 where the geometry trains the models of that amplitude"),
        "kernel": variable(("output", "amplitude"), np.full((n_out, n_amp), s["kernel"], dtype=object), "1",
                           "correlation function of the model"),
        "scale": variable(("output", "amplitude", "parameter"), scale, "1", "correlation length theta per parameter"),
        "nugget": variable(("output", "amplitude"), nugget, "1", "nugget factor (fraction of sigma^2)"),
        "status": variable(("output", "amplitude"), status, "1", "model status", flag_values=[0, 1, 2],
                           flag_meanings=STATUS_MEANINGS),
        "n_training": variable(("output", "amplitude"), np.tile(n_train, (n_out, 1)), "1",
                               "number of training points of the model"),
        "log_likelihood": variable(("output", "amplitude"), loglik, "1", "maximised reduced log-likelihood"),
        "q2": variable(("output", "amplitude"), q2s, "1", "leave-one-out predictivity coefficient Q2"),
        **per_output,
    }
    coords = {
        "output": variable("output", np.array(outputs, dtype=object), "1", "Kriging output"),
        "amplitude": ("amplitude", dataset["amplitude"].values, amp_attrs),
        "parameter": variable("parameter", np.array(PARAMETERS, dtype=object), "1", "shape parameter"),
        "geometry": variable("geometry", geometry, "1", "training geometry"),
    }
    import openturns as ot

    attrs = {"openturns_version": ot.__version__, "kernel": s["kernel"], "n_starts": s["n_starts"],
             "seed": s["seed"], "scale_bounds": list(s["scale_bounds"]), "scale_bounds_unit": "kappa-domain width (2)",
             "nugget_setting": list(np.atleast_1d(s["nugget"])), "min_training": s["min_training"]}
    return xr.Dataset(data, coords=coords, attrs=attrs)


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
