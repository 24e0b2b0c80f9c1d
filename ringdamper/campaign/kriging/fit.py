"""Maximum-likelihood fit of one ordinary-Kriging model with OpenTURNS (paper §3.2.1).

OpenTURNS ``GaussianProcessFitter`` with a constant basis: for given θ and ν, β̂ = (1ᵀR⁻¹y)/(1ᵀR⁻¹1)
(generalised least squares) and σ̂² = (y - β̂1)ᵀR⁻¹(y - β̂1)/(N - 1) (the unbiased analytical amplitude),
R = [ρ_θ(xᵢ - xⱼ)] + νI (kernels in :mod:`.gp`); θ maximises the concentrated (reduced) log-likelihood

    ℓ(θ) = -½ (log det(σ̂² R) + N - 1) - N log √(2π)

by Cobyla from ``n_starts`` starting points (a seeded log-uniform Latin hypercube over the bounds of
:mod:`.settings`, OpenTURNS ``MultiStart``), then polished by L-BFGS-B in log θ (numpy ℓ of
:meth:`.gp.GPModel.log_likelihood`, equal to OpenTURNS', climbing its analytic gradient
:func:`.gp.log_likelihood_gradient`): OpenTURNS' solver works on θ mapped linearly onto [0, 1], where
the short lengths a response with jumps asks for (θ ∈ [0.1, 0.3] is 2 % of the interval) are poorly
resolved; it stopped on the lower bound θ₁ = 0.1 where ℓ rises by 1-5 at θ₁ ≈ 0.2
(docs/surrogate.md, *Responses with jumps*). A polished θ is handed back to OpenTURNS (fixed parameters,
amplitude σ̂) so that the fitted result, and the cross-check below, stay OpenTURNS'. ν is fixed or,
given as [low, high], estimated: the fit above is run at NUGGET_PROFILE log-spaced values of ν (the
profile: OpenTURNS cannot resolve a ν spanning decades on its [0, 1] scale), each polished in log θ and
log ν together within [low, high], and the one of largest ℓ kept. The profile's ends start the two
modes the likelihood of scattered data has (interpolate the scatter with short lengths, or take it as
noise: docs/surrogate.md, *Branch scatter*); the starts are fixed by the settings, so the fit is
deterministic.

Data whose spread is below CONSTANT_RTOL × max|y| (round-off; or × the output's scale over the campaign,
when the caller gives it) give the constant model β = mean(y), σ = 0
without OpenTURNS. Every fitted model is checked twice: its amplitude against the closed-form σ̂ at
OpenTURNS' optimum (AMPLITUDE_RTOL; σ̂ replaces it otherwise), and the numpy predictor of :mod:`.gp`
against OpenTURNS' ``GaussianProcessRegression`` (MATCH_RTOL of the data spread; a larger gap is the sign
of an ill-conditioned R, which OpenTURNS regularises silently).

References: Sacks, Welch, Mitchell & Wynn (1989) Stat. Sci. 4: 409–423; Jones, Schonlau & Welch (1998)
J. Glob. Optim. 13: 455–492 (the concentrated likelihood).
"""

from __future__ import annotations

import logging

import numpy as np

from .gp import GPModel, _squared_differences, log_likelihood_gradient
from .settings import DOMAIN_WIDTH, check_settings

log = logging.getLogger(__package__)  # one logger for the package: ringdamper.campaign.kriging

MATCH_RTOL = 1.0e-6  # allowed numpy/OpenTURNS prediction gap, fraction of the data spread
AMPLITUDE_RTOL = 1.0e-6  # OpenTURNS' amplitude vs the closed-form ML estimate at its θ, ν
COINCIDENT = 1.0e-9  # a check point this close to a training input (κ units) coincides with it
NUGGET_PROFILE = 5  # log-spaced starting nugget values when the nugget is estimated
# data whose spread is below this times max|y| (round-off) are taken as constant: no process is fitted
CONSTANT_RTOL = 1.0e-12


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


def _fit_ot_from_nugget(x: np.ndarray, y: np.ndarray, s: dict, nugget: float):
    """OpenTURNS' multistart fit of θ at the nugget ``nugget``, then the polish of :func:`_polish` (θ, and ν
    too when it is estimated: within the ``surrogate.nugget`` interval); the polished parameters go back
    to OpenTURNS with fixed parameters and the ML amplitude σ̂."""
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
    result = fitter.getResult()
    start = np.clip(np.array(result.getCovarianceModel().getScale()), lower, upper)
    nugget_bounds = s["nugget"] if isinstance(s["nugget"], tuple) else None
    polished = _polish(x, y, s["kernel"], start, nugget, lower, upper, nugget_bounds)
    if polished is None:
        return result
    scale, nugget, sigma = polished
    cov.setScale(scale)
    cov.setNuggetFactor(nugget)
    cov.setAmplitude([sigma])
    fixed = ot.GaussianProcessFitter(x, y[:, None], cov, ot.ConstantBasisFactory(dim).build())
    fixed.setOptimizeParameters(False)
    fixed.run()
    return fixed.getResult()


def _polish(x, y, kernel: str, scale, nugget: float, lower, upper, nugget_bounds=None):
    """(θ, ν, σ̂) maximising ℓ by L-BFGS-B in log θ (and log ν within ``nugget_bounds`` when given; ν
    fixed otherwise) from (``scale``, ``nugget``), θ within [lower, upper], with the analytic gradient of
    :func:`.gp.log_likelihood_gradient`; None if ℓ does not rise above its value at the start (by more
    than 1e-9 |ℓ|)."""
    from scipy.optimize import minimize

    d, free_nugget = len(scale), nugget_bounds is not None

    def negative_ll(p):
        nu = float(np.exp(p[-1])) if free_nugget else nugget
        try:
            ell, grad = log_likelihood_gradient(kernel, x, y, np.exp(p[:d]), nu)
        except np.linalg.LinAlgError:
            return np.finfo(float).max, np.zeros_like(p)
        return -ell, -(grad if free_nugget else grad[:d])

    start, bounds = np.log(scale), list(zip(np.log(lower), np.log(upper)))
    if free_nugget:
        start, bounds = np.append(start, np.log(nugget)), bounds + [tuple(np.log(nugget_bounds))]
    f0 = negative_ll(start)[0]
    res = minimize(negative_ll, start, method="L-BFGS-B", jac=True, bounds=bounds)
    if not res.fun < f0 - 1e-9 * abs(f0):
        return None
    theta = np.clip(np.exp(res.x[:d]), lower, upper)
    nu = float(np.clip(np.exp(res.x[-1]), *nugget_bounds)) if free_nugget else nugget
    return theta, nu, GPModel(kernel, theta, 1.0, nu, 0.0, x, y).ml_sigma()


def fit_ot(x: np.ndarray, y: np.ndarray, settings: dict | None = None):
    """Maximum-likelihood ordinary Kriging with OpenTURNS: the ``GaussianProcessFitterResult``.

    An estimated nugget (``nugget: [low, high]``) is profiled and polished: the fit starts at NUGGET_PROFILE
    log-spaced values, θ and ν are polished together from each, and the one of largest likelihood is kept
    (OpenTURNS' optimiser works on the parameters linearly scaled to [0, 1], where it cannot resolve a
    nugget spanning decades)."""
    s = check_settings(settings)
    x, y = np.ascontiguousarray(x, dtype=float), np.ascontiguousarray(y, dtype=float)  # layout-free sums
    nuggets = np.geomspace(*s["nugget"], NUGGET_PROFILE) if isinstance(s["nugget"], tuple) else [s["nugget"]]
    results = [_fit_ot_from_nugget(x, y, s, float(nu)) for nu in nuggets]
    return max(results, key=lambda r: _model(r, s["kernel"], x, y).log_likelihood())


def _model(result, kernel: str, x, y) -> GPModel:
    cm = result.getCovarianceModel()
    return GPModel(kernel, np.array(cm.getScale()), cm.getAmplitude()[0], cm.getNuggetFactor(),
                   result.getTrendCoefficients()[0], x, y)


def is_constant_data(y: np.ndarray, scale: float = 0.0) -> bool:
    """Spread of ``y`` below CONSTANT_RTOL × max(max|y|, ``scale``): round-off about a constant."""
    return np.ptp(y) <= CONSTANT_RTOL * max(np.max(np.abs(y)), scale)


def fit_model(x: np.ndarray, y: np.ndarray, settings: dict | None = None, name: str = "y",
              constant: bool | None = None):
    """Fit one model; returns (GPModel, reduced log-likelihood). Constant data give the constant model
    β = mean(y), σ = 0 without OpenTURNS: those the caller says are (``constant``; e.g. ζ = ±1e-17 when
    the output reaches 1e-3 elsewhere) or, by default, those whose spread is below CONSTANT_RTOL × max|y|
    (e.g. ζ ≡ 0). Non-finite data raise ValueError naming ``name``."""
    s = check_settings(settings)
    x, y = np.ascontiguousarray(x, dtype=float), np.ascontiguousarray(y, dtype=float)  # layout-free sums
    if x.ndim != 2 or y.shape != (len(x),):
        raise ValueError(f"{name}: inputs must be (n, d) and outputs (n,), got {x.shape} and {y.shape}")
    bad = ~np.isfinite(y) | ~np.all(np.isfinite(x), axis=1)
    if bad.any():
        rows = np.flatnonzero(bad)[:10].tolist()
        raise ValueError(f"{name}: {bad.sum()} non-finite training value(s) at rows {rows}; "
                         "filter failed geometries (mask) before fitting")
    if len(y) < 2:
        raise ValueError(f"{name}: {len(y)} training point(s); at least 2 are needed")
    if is_constant_data(y) if constant is None else constant:
        return GPModel(s["kernel"], np.full(x.shape[1], np.nan), 0.0, 0.0, float(np.mean(y)), x, y), np.nan
    result = fit_ot(x, y, s)
    model = _model(result, s["kernel"], x, y)
    sigma = model.ml_sigma()
    if abs(sigma - model.sigma) > AMPLITUDE_RTOL * sigma:
        # OpenTURNS may return its starting amplitude (1) instead of the analytical estimate at the
        # optimum θ, which puts the predictive σ off by orders of magnitude. The ML amplitude at θ, ν
        # is closed-form, so it is restored.
        log.warning("%s: OpenTURNS amplitude %.3g is not the ML estimate %.3g at its optimum; using the latter",
                    name, model.sigma, sigma)
        model = GPModel(s["kernel"], model.scale, sigma, model.nugget, model.beta, x, y)
    _check_against_ot(model, result, name)
    return model, model.log_likelihood()


def _check_against_ot(model: GPModel, fitter_result, name: str) -> None:
    """Warn when the numpy predictor departs from OpenTURNS' GaussianProcessRegression (at the midpoints
    of successive training points) by more than MATCH_RTOL of the data spread: R is then too
    ill-conditioned (OpenTURNS regularises its Cholesky factor silently); a nugget cures it. Midpoints
    that coincide with a training input are left out: there OpenTURNS adds σ²ν to the cross-covariance
    and returns the noisy observation (:mod:`.gp`), a gap of order ν, not of conditioning (a factorial
    design has such midpoints)."""
    import openturns as ot

    algo = ot.GaussianProcessRegression(fitter_result)
    algo.run()
    mid = 0.5 * (model.x[:-1] + model.x[1:])
    mid = mid[np.min(np.sum(_squared_differences(mid, model.x), axis=0), axis=1) > COINCIDENT ** 2]
    if not len(mid):
        return
    ours, _ = model.predict(mid, with_std=False)
    gap = np.max(np.abs(ours - np.asarray(algo.getResult().getMetaModel()(mid)).ravel())) / np.ptp(model.y)
    if gap > MATCH_RTOL:
        log.warning("%s: numpy and OpenTURNS predictions differ by %.2g of the data spread (ill-conditioned "
                    "correlation matrix, scale %s); consider a nugget", name, gap, np.round(model.scale, 3))
