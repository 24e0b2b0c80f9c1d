"""Condition number of the Newton Jacobian at every converged point of a backbone (docs/nonlinear_core.md §4.6).

The EPMC point ``z = [y, ω, ξ]`` solves ``r(z) = 0``
(:class:`ringdamper.nonlinear.harmonic_balance.epmc.EPMCProblem`). Newton stops when its correction ``δz = −J⁻¹ r``
is below ``tol`` in the scaled unknowns ``z_i / scale_i``
(:meth:`ringdamper.nonlinear.harmonic_balance.epmc.EPMCProblem.scale`), so the returned
point is within about ``tol`` of the exact root, in that measure, whatever the Jacobian. What rounding
adds is ``J⁻¹ δr`` with ``δr`` the rounding of the residual, ``|δr_i| ≈ ε · (size of the terms of row i)``. In the
scaled unknowns and with every row divided by its largest Jacobian entry (the size of its terms at the scaled unit
step), that is at most about ``κ ε`` with

    κ = κ₁(D_r J D_c),     D_c = diag(scale(z)),     D_r = diag(1 / max_j |J_ij D_c,jj|),

the 1-norm condition number of the equilibrated Jacobian. Two BLAS kernels (other summation orders,
FMA or not) give two such roundings, so the two converged points differ by up to ``2 tol + 2 κ ε``
scaled: with ``tol = 1e-8`` the first term is 2e-8, and the second exceeds 1e-6 when
``κ > 1e-6 / (2 ε) ≈ 2.25e9`` (:data:`ILL_CONDITIONED`).

``J`` is that of :meth:`ringdamper.nonlinear.harmonic_balance.epmc.EPMCProblem.fun` at the point, in its
gauge state (its pinned rigid-body directions: :meth:`Backbone.problem`), with the trivial unknowns
(unit columns in the core rows: contact slots of pairs open over the whole period) eliminated as the Newton does:
``A = J_NN − J_NT J_TN``. κ is LAPACK's estimate ``1 / dgecon`` from the LU of ``D_r A D_c`` (Higham's 1-norm
estimator, within a
factor of a few of the exact value; :meth:`ringdamper.nonlinear.solvers.newton.Factorization.condition`). The
natural continuation forms that LU at every grid value it lands on, for the point's tangent, and keeps
the estimate (``Backbone.condition``); the points solved otherwise (the grid values past a fold, solved
from the arc-length branch; a single point solved again at another H) get theirs here.

The points solved by the stuck shortcut (all pairs stick: ``y(α) = (α/α₁) y(α₁)``, same ω and ξ)
share one Jacobian up to ``J(α) = S_r J(α₁) S_c`` (:func:`ringdamper.nonlinear.harmonic_balance.epmc._stuck_points`):
``S_r`` scales the amplitude row, which ``D_r`` undoes, and ``S_c`` the ω and ξ columns by ``α/α₁``
as ``scale(z)`` scales the ``y`` columns, so ``D_r J D_c`` and κ are those of the first of them.

κ is reported to :data:`SIGNIFICANT_DIGITS` significant digits (:func:`reported`): the estimate is
good to a factor of a few only, and its last bits depend on the memory alignment the BLAS kernel
meets (two runs in one process differ by ~1e-16 relative), which the rounding keeps out of dnnm.nc,
so a rerun reproduces the file bit for bit.
"""
from __future__ import annotations

import numpy as np

from ringdamper.nonlinear.harmonic_balance.epmc import Backbone
from ringdamper.nonlinear.solvers.jacobian import dense
from ringdamper.nonlinear.solvers.newton import Factorization
from ringdamper.status import usable_status

#: κ above which rounding alone may move a converged point by more than 1e-6 (relative, scaled
#: unknowns): 1e-6 / (2 ε), two kernels each off by κ ε (module docstring)
ILL_CONDITIONED = 1e-6 / (2 * np.finfo(float).eps)

#: significant digits of the reported κ (module docstring)
SIGNIFICANT_DIGITS = 4

#: relative agreement of ``y(α_i) α₁ / α_i`` with ``y(α₁)`` (and of ω, ξ) that makes point ``i`` a
#: scaled copy of point ``α₁`` (the stuck shortcut builds them exactly so, to rounding)
SCALED_COPY_TOL = 1e-12


def equilibrated_condition(J: np.ndarray, trivial: np.ndarray | None, scale: np.ndarray) -> float:
    """κ₁ of ``D_r A D_c`` (module docstring): ``J`` with its trivial unknowns eliminated, columns
    scaled by ``scale``, rows by their largest entry. ``inf`` if a row or the LU is singular. ``J`` is
    overwritten."""
    n_core = J.shape[0] if trivial is None else trivial.size
    return Factorization(J, trivial, n_core, overwrite=True, scale=scale).condition()


def point_condition(backbone: Backbone, i: int) -> float:
    """κ (module docstring) of grid point ``i`` of ``backbone``, from its Jacobian at the solution."""
    problem = backbone.problem(i)
    z = backbone.unknowns(i)
    ev = problem.fun(z, np.log(backbone.alpha[i]), True)
    return equilibrated_condition(dense(ev.J), ev.trivial, problem.scale(z))


def backbone_conditions(backbone: Backbone) -> np.ndarray:
    """κ of every usable point (status 0 or 3) of ``backbone``, NaN elsewhere: the estimate the
    continuation made where it factorised the point's Jacobian (``backbone.condition``), else computed
    here. The points that are scaled copies of the first (the stuck shortcut's) take its κ."""
    known = np.full(backbone.alpha.size, np.nan) if backbone.condition is None else backbone.condition
    kappa = np.full(backbone.alpha.size, np.nan)
    for i in np.flatnonzero(usable_status(np.asarray(backbone.status))):
        shared = i > 0 and np.isfinite(kappa[0]) and _scaled_copy(backbone, 0, i)
        if shared:
            kappa[i] = kappa[0]
        elif np.isfinite(known[i]):
            kappa[i] = known[i]
        else:
            kappa[i] = point_condition(backbone, i)
    return reported(kappa)


def reported(kappa: np.ndarray) -> np.ndarray:
    """``kappa`` rounded to :data:`SIGNIFICANT_DIGITS` significant digits (NaN and inf kept)."""
    out = np.array(kappa, dtype=float)
    ok = np.isfinite(out) & (out > 0)
    unit = 10.0 ** (np.floor(np.log10(out[ok])) - (SIGNIFICANT_DIGITS - 1))
    out[ok] = np.round(out[ok] / unit) * unit
    return out


def _scaled_copy(backbone: Backbone, first: int, i: int) -> bool:
    """Point ``i`` is point ``first`` scaled by the amplitude ratio: its contact slots within
    :data:`SCALED_COPY_TOL` of ``α_i/α_first`` times those of ``first`` relative to the largest slot, its
    modal coordinates of all harmonics so relative to the largest coordinate, same ω and ξ."""
    ratio = backbone.alpha[i] / backbone.alpha[first]
    for parts in ([backbone.d], backbone.eta):
        size = max(np.max(np.abs(x[first]), initial=0.0) for x in parts) * ratio
        error = max(np.max(np.abs(x[i] - ratio * x[first]), initial=0.0) for x in parts)
        if not error <= SCALED_COPY_TOL * size:
            return False
    return (backbone.omega[i] == backbone.omega[first]
            and abs(backbone.xi[i] - backbone.xi[first]) <= SCALED_COPY_TOL * abs(backbone.omega[first]))
