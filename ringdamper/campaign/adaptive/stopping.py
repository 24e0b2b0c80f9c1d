"""The stop decision of a round, on training-side evidence only (the validation rings never enter):

* accuracy: every output's normalised leave-one-out error ε_o (:func:`.model.normalised_loo`) is at
  most ``loo_tolerance``;
* stability: over the last ``stable_rounds`` rounds the predicted optimum moved by at most
  ``kappa_tolerance`` in every kappa_i and its predicted zeta_max by at most ``zeta_tolerance`` relative.

Both must hold: a small leave-one-out error says the models are right where the rings are, a settled
optimum says the answer no longer moves as rings are added. Otherwise the campaign stops at the budget:
``n_max`` training rings computed (not an error; the record keeps the last estimates).
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


def decide(loo: dict, optima: list[dict], n_computed: int, adaptive: dict) -> dict:
    """Stop decision after a round fitted on ``n_computed`` training rings: ``optima`` the predicted
    optima of every round so far (this one last), ``adaptive`` the ``sampling.adaptive`` settings."""
    worst = max(loo.values(), key=lambda e: -np.inf if np.isnan(e) else e)
    accurate = bool(np.isfinite(worst) and worst <= adaptive["loo_tolerance"])
    recent = optimum_changes(optima)[-adaptive["stable_rounds"]:]
    stable = len(recent) == adaptive["stable_rounds"] and all(
        c["kappa"] <= adaptive["kappa_tolerance"] and c["zeta_max"] <= adaptive["zeta_tolerance"] for c in recent)
    if accurate and stable:
        reason = CONVERGED
    elif n_computed >= adaptive["n_max"]:
        reason = BUDGET
    else:
        reason = None
    return {"stop": reason is not None, "reason": reason, "worst_loo": float(worst), "accurate": accurate,
            "stable": bool(stable), "optimum_changes": recent}
