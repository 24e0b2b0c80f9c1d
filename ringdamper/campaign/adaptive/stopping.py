"""The stop decision of a round, on training-side evidence only (the validation rings never enter):

* accuracy: every output's estimated validation error, relative to its spread over the domain
  (:func:`.accuracy.estimates`, the one named by ``RULE_ESTIMATE``: the calibrated predictive variance
  averaged over the domain), is at most
  its ``rmse_tolerance`` (by default the relative validation RMSE of the paper's fixed 100-ring
  design): the loop stops when it can promise the paper design's accuracy;
* stability: over the last ``stable_rounds`` rounds the predicted optimum moved by at most
  ``kappa_tolerance`` in every kappa_i and its predicted zeta_max by at most ``zeta_tolerance`` relative.

Both must hold: an accurate surrogate reads the right backbones everywhere, a settled optimum says the
answer no longer moves as rings are added. Otherwise the campaign stops at the budget: ``n_max``
training rings computed (not an error; the record keeps the last estimates).
"""
from __future__ import annotations

import numpy as np

CONVERGED, BUDGET = "converged", "budget"


def optimum_changes(optima: list[dict]) -> list[dict]:
    """Per successive pair of round optima: the largest |Δkappa_i| and the relative |Δzeta_max|."""
    changes = []
    for previous, current in zip(optima, optima[1:]):
        dk = float(np.max(np.abs(np.subtract(current["kappa"], previous["kappa"]))))
        dz = abs(current["zeta_max"] - previous["zeta_max"]) / abs(current["zeta_max"])
        changes.append({"kappa": dk, "zeta_max": float(dz)})
    return changes


def accuracy_ratios(estimate: dict, tolerance: dict) -> dict:
    """output -> estimated relative error / its tolerance (accurate at <= 1); NaN for an output whose
    models were not fitted. Every output of ``estimate`` needs a tolerance."""
    missing = sorted(set(estimate) - set(tolerance))
    if missing:
        raise ValueError(f"sampling.adaptive.rmse_tolerance lacks {missing}")
    return {o: float(e / tolerance[o]) for o, e in estimate.items()}


def decide(estimate: dict, optima: list[dict], n_computed: int, adaptive: dict) -> dict:
    """Stop decision after a round fitted on ``n_computed`` training rings: ``estimate`` this round's
    relative error estimates (output -> value), ``optima`` the predicted optima of every round so far
    (this one last), ``adaptive`` the ``sampling.adaptive`` settings."""
    ratios = accuracy_ratios(estimate, adaptive["rmse_tolerance"])
    finite = [r for r in ratios.values() if np.isfinite(r)]
    worst = max(finite) if finite else float("nan")
    accurate = bool(finite) and worst <= 1.0
    recent = optimum_changes(optima)[-adaptive["stable_rounds"]:]
    stable = len(recent) == adaptive["stable_rounds"] and all(
        c["kappa"] <= adaptive["kappa_tolerance"] and c["zeta_max"] <= adaptive["zeta_tolerance"] for c in recent)
    if accurate and stable:
        reason = CONVERGED
    elif n_computed >= adaptive["n_max"]:
        reason = BUDGET
    else:
        reason = None
    return {"stop": reason is not None, "reason": reason, "worst_ratio": float(worst), "accurate": accurate,
            "ratios": ratios, "stable": bool(stable), "optimum_changes": recent}
