"""The stop decision of a round, on training-side evidence only (the validation rings never enter):

* accuracy: every output's normalised leave-one-out error ε_o (:func:`.model.normalised_loo`) is
  settled: at most ``loo_tolerance``, or on a plateau, where ``stable_rounds`` more rounds moved it by
  less than the fraction ``loo_plateau`` of the best earlier value, either way,
  ``(1 - loo_plateau) · m < ε_o(k) ≤ (1 + loo_plateau) · m`` with ``m = min_{j ≤ k - stable_rounds} ε_o(j)``
  (``loo_plateau = 0`` turns the plateau off). An error that rose above the band is not settled: the
  rings added since found responses the earlier models had not seen (an adaptive design's rings sit
  where the response is hardest), and the loop goes on until the models have caught up with them;
* stability: over the last ``stable_rounds`` rounds the predicted optimum moved by at most
  ``kappa_tolerance`` in every kappa_i and its predicted zeta_max by at most ``zeta_tolerance`` relative.

Both must hold: a small (or no longer shrinking) leave-one-out error says more rings of this kind no
longer make the models better, a settled optimum says the answer no longer moves as rings are added.
The plateau matters where an output has jumps (contact separation at the top amplitudes): there its
leave-one-out error stays above any tolerance the smooth part meets, and without the plateau the loop
would always run to the budget. Otherwise the campaign stops at the budget: ``n_max`` training rings
computed (not an error; the record keeps the last estimates).
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


def settled_outputs(loo_history: list[dict], adaptive: dict) -> dict:
    """output -> "tolerance", "plateau" or None (not settled) for the last of ``loo_history`` (the
    normalised leave-one-out errors of every round so far, this one last; module docstring)."""
    lag, plateau = adaptive["stable_rounds"], adaptive["loo_plateau"]
    out = {}
    for name, e in loo_history[-1].items():
        earlier = [r[name] for r in loo_history[:-lag] if np.isfinite(r[name])]
        if np.isnan(e) or e <= adaptive["loo_tolerance"]:
            out[name] = "tolerance"
        elif plateau > 0 and earlier and (1 - plateau) * min(earlier) < e <= (1 + plateau) * min(earlier):
            out[name] = "plateau"
        else:
            out[name] = None
    return out


def decide(loo_history: list[dict], optima: list[dict], n_computed: int, adaptive: dict) -> dict:
    """Stop decision after a round fitted on ``n_computed`` training rings: ``loo_history`` the
    normalised leave-one-out errors and ``optima`` the predicted optima of every round so far (this one
    last), ``adaptive`` the ``sampling.adaptive`` settings."""
    loo = loo_history[-1]
    worst = max(loo.values(), key=lambda e: -np.inf if np.isnan(e) else e)
    settled = settled_outputs(loo_history, adaptive)
    accurate = bool(np.isfinite(worst) and all(settled.values()))
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
            "plateau": sorted(k for k, v in settled.items() if v == "plateau"),
            "stable": bool(stable), "optimum_changes": recent}
