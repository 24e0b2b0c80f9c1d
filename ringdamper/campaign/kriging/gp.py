"""Ordinary Kriging in numpy: correlation kernels, predictor and variance, leave-one-out (paper §3.2).

Model (paper Eq. 7): y(x) = β + Z(x), x = κ ∈ [-1, 1]³, Z a centred stationary Gaussian process of
covariance σ² (ρ_θ(x - x') + ν δ_{x,x'}), with an anisotropic correlation ρ_θ of the scaled distance
d = ‖(x - x') / θ‖ (θ one scale per parameter) and ν a nugget factor:

- ``matern52``:                   ρ = (1 + √5 d + 5 d²/3) exp(-√5 d)
- ``squared_exponential``:        ρ = exp(-d²/2)

(both exactly OpenTURNS' ``MaternModel(ν=5/2)`` / ``SquaredExponential``). With R = [ρ_θ(xᵢ - xⱼ)] + νI,
the trend and amplitude that maximise the likelihood at given θ, ν are closed-form: β̂ = (1ᵀR⁻¹y)/(1ᵀR⁻¹1)
(generalised least squares) and σ̂² = (y - β̂1)ᵀR⁻¹(y - β̂1)/(N - 1) (OpenTURNS' unbiased amplitude).

Predictor (paper Eq. 8) and ordinary-Kriging variance, with r₀ = [ρ_θ(x₀ - xᵢ)] (no nugget) and R = LLᵀ
(so that r₀ᵀR⁻¹r₀ = ‖L⁻¹r₀‖²):

    ŷ(x₀)  = β + r₀ᵀ R⁻¹ (y - β1)
    s²(x₀) = σ² (1 + ν - r₀ᵀR⁻¹r₀ + (1 - 1ᵀR⁻¹r₀)² / (1ᵀR⁻¹1))

The last term accounts for the estimation of β (Rasmussen & Williams §2.7); this is exactly what
OpenTURNS' ``GaussianProcessRegression`` / ``GaussianProcessConditionalCovariance`` compute at any input
that does not coincide with a training input (there OpenTURNS also adds σ²ν to the cross-covariance, so
its mean jumps to the noisy observation; ours stays continuous).

Leave-one-out with fixed θ, σ, ν (Dubrule 1983, "Cross validation of kriging in a unique
neighborhood", Math. Geol. 15: 687–699): with the ordinary-Kriging system K = [[R, 1], [1ᵀ, 0]],

    eᵢ = yᵢ - ŷ₋ᵢ(xᵢ) = [K⁻¹ (y; 0)]ᵢ / [K⁻¹]ᵢᵢ = [R⁻¹(y - β̂1)]ᵢ / [R⁻¹ - R⁻¹11ᵀR⁻¹/(1ᵀR⁻¹1)]ᵢᵢ,

where ŷ₋ᵢ re-estimates β on the other N - 1 points; Q² = 1 - Σeᵢ² / Σ(yᵢ - ȳ)². The leave-one-out
predictive variance is s²₋ᵢ = σ² / [K⁻¹]ᵢᵢ (same reference).

Variance calibration. The ML amplitude σ̂² makes the standardised *training* residuals have unit
variance under the model; with few points, estimated θ and a misspecified correlation the predictive
σ is then too small away from the data, and the residuals are heavier-tailed than a Gaussian, so the
±2σ band covers less than its nominal share. The predictive σ is therefore scaled so that the band
holds the nominal share of the normalised leave-one-out residuals tᵢ = |eᵢ| / s₋ᵢ (the jackknife with
normalised conformity scores: Barber, Candès, Ramdas & Tibshirani 2021, "Predictive inference with
the jackknife+", Ann. Stat. 49: 486–507; Lei, G'Sell, Rinaldo, Tibshirani & Wasserman 2018,
"Distribution-free predictive inference for regression", JASA 113: 1094–1111, §5.2):

    q = t₍ₖ₎,  k = ⌈(N + 1) p⌉ (capped at N),  p = P(|Z| ≤ 2) = 0.9545,     s(x₀) ← (q / 2) s(x₀),

stored per model as the variance factor ψ = (q/2)² (ψ = 1 reproduces the ML variance). The rate is
empirical, not guaranteed (the jackknife's guarantee is 1 − 2(1 − p)); docs/method_limits.md §3
charts the coverage before and after against the training size and near the boundary.

References: Sacks, Welch, Mitchell & Wynn (1989) Stat. Sci. 4: 409–423; Rasmussen & Williams (2006)
Gaussian Processes for Machine Learning §2.7.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as sla
from scipy.linalg import blas

KERNELS = ("matern52", "squared_exponential")
SIGMA_BAND = 2.0  # the predictive band ±2σ ...
BAND_PROBABILITY = 0.9545  # ... and its nominal coverage P(|Z| <= 2) for a Gaussian prediction


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

    def log_likelihood(self) -> float:
        """Reduced (concentrated) log-likelihood at the model's θ, ν: ℓ = -½ (N log σ̂² + log det R + N - 1)
        - N log √(2π), σ̂ of :meth:`ml_sigma` (OpenTURNS' ``getOptimalLogLikelihood``; NaN if constant)."""
        if self.is_constant:
            return np.nan
        n = len(self.y)
        log_det = -2.0 * np.sum(np.log(np.diag(self.Linv)))  # det R = 1 / det(L⁻¹)²
        return float(-0.5 * (n * np.log(self.ml_sigma() ** 2) + log_det + n - 1) - n * np.log(np.sqrt(2 * np.pi)))

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


def _correlation_and_log_scale_derivatives(kernel: str, sq: np.ndarray, scale: np.ndarray):
    """ρ_θ (N, N) (:func:`correlation`) and ∂ρ/∂log θ_k (d, N, N) from the squared differences ``sq``
    (d, N, N): with d² = Σ_k Δ_k²/θ_k², ∂d²/∂log θ_k = −2Δ_k²/θ_k², so ∂ρ/∂log θ_k = −2 (dρ/dd²) Δ_k²/θ_k²,
    where −2 dρ/dd² = (5/3)(1 + √5 d) e^{−√5 d} (Matérn 5/2) or ρ itself (squared exponential)."""
    weighted = sq / scale[:, None, None] ** 2
    d2 = weighted.sum(axis=0)
    rho = correlation(kernel, d2.copy())
    if kernel == "matern52":
        d = np.sqrt(5.0 * d2)
        slope = (5.0 / 3.0) * (1.0 + d) * np.exp(-d)
    else:
        slope = rho
    return rho, slope[None] * weighted


def log_likelihood_gradient(kernel: str, x: np.ndarray, y: np.ndarray, scale: np.ndarray,
                            nugget: float) -> tuple[float, np.ndarray]:
    """Reduced log-likelihood ℓ of :meth:`GPModel.log_likelihood` at θ = ``scale``, ν = ``nugget`` and its
    gradient with respect to (log θ₁, …, log θ_d, log ν).

    With R = ρ_θ + νI, a = R⁻¹(y − β̂1), S = (y − β̂1)ᵀa = (N − 1)σ̂² (β̂ makes S stationary, so it does not
    enter the derivative) and ∂S/∂p = −aᵀ(∂R/∂p)a,

        ∂ℓ/∂p = ½ Σᵢⱼ Wᵢⱼ (∂R/∂p)ᵢⱼ,      W = N a aᵀ / S − R⁻¹,

    with ∂R/∂log θ_k = ∂ρ/∂log θ_k and ∂R/∂log ν = νI (Rasmussen & Williams 2006, §5.4.1, for the
    concentrated form). Raises ``np.linalg.LinAlgError`` when R is not positive definite."""
    x, y, scale = np.asarray(x, float), np.asarray(y, float), np.asarray(scale, float)
    n = len(y)
    rho, drho = _correlation_and_log_scale_derivatives(kernel, _squared_differences(x, x), scale)
    R = rho + nugget * np.eye(n)
    cho = sla.cho_factor(R, lower=True)
    Rinv = sla.cho_solve(cho, np.eye(n))
    Rinv_1, Rinv_y = Rinv.sum(axis=1), Rinv @ y
    beta = Rinv_1 @ y / Rinv_1.sum()
    a = Rinv_y - beta * Rinv_1
    S = (y - beta) @ a
    log_det = 2.0 * np.sum(np.log(np.diag(cho[0])))
    ell = -0.5 * (n * np.log(S / (n - 1)) + log_det + n - 1) - n * np.log(np.sqrt(2 * np.pi))
    W = (n / S) * np.outer(a, a) - Rinv
    grad = np.empty(len(scale) + 1)
    grad[:-1] = 0.5 * np.einsum("ij,kij->k", W, drho)
    grad[-1] = 0.5 * nugget * np.trace(W)
    return float(ell), grad


def q2(y: np.ndarray, residuals: np.ndarray) -> float:
    """Q² = 1 - Σe² / Σ(y - ȳ)² (NaN for constant y)."""
    ss = np.sum((y - np.mean(y)) ** 2)
    return float(1.0 - np.sum(residuals**2) / ss) if ss > 0 else np.nan

