"""Our campaign's figures beside the paper's published ones (Sun, Denimal, Yuan & Salles 2022).

Every paper value carries the section it is read from. The paper's rings are not ours: the model's
free dimensions (disk web and hub, the rim's arm, the ring's axial position; docs/model.md) and the
contact parameters (friction coefficient and contact stiffnesses, calibrated once on the default
ring to the paper's ζ_max, its amplitude and the frequency drop there; docs/calibration.md) are our
choices where the paper is silent, so only the default ring's damping peak is matched by
construction and every other number is a prediction of our model.
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from .summary import dnnm_summary

# paper values: (quantity, value, unit, source)
DEFAULT = {
    "omega0_low": (2.195, "§2.3 Fig. 5 and §2.6 (linear sticking frequency, Fig. 8a)"),
    "zeta_max": (0.15e-2, "§2.6 (Fig. 8b); §3.4's summary quotes 0.12 %"),
    "q_at_zeta_max": (0.164e-3, "§2.6 (Fig. 8b)"),
    "omega0_at_zeta_max": (2.187, "§2.6 (Fig. 8a)"),
}
CASE_A = {  # kappa = (1, 0, 0)
    "omega0_low": (2.185, "§3.1.3 (Fig. 12a, case A)"),
    "zeta_max": (0.28e-2, "§3.1.3 (Fig. 12b, case A)"),
}
OPTIMUM = {
    "kappa": ((1.0, -1.0, -1.0), "§3.3.2 and §3.4"),
    "zeta_max": (0.35e-2, "§3.3.2 (Fig. 17b); §3.4's summary quotes 0.36 %"),
    "omega0_low": (2.182, "§3.4 (ω0 reduced from 2.195 to 2.182)"),
}
SOBOL_LEVEL = 0.05e-3  # m, Fig. 18a
SOBOL_ZETA = {"first_order": (0.41, 0.27, 0.21), "total_order": (0.46, 0.39, 0.33)}
SOBOL_SOURCE = "§3.3.3 (Fig. 18a, |q_res,z| = 0.05 mm, global on [-1, 1]^3)"
TABLE3 = {"gamma_N": (20.0, 60.0, 80.0, 101.0), "default_mm": (0.069, 0.191, 0.301, 0.439),
          "optimum_mm": (0.049, 0.114, 0.145, 0.215), "reduction_pct": (29.0, 40.3, 51.8, 51.0)}

AGREE_PCT = 10.0        # ours "agree" with the paper within this (ω0: within AGREE_OMEGA_PCT)
AGREE_OMEGA_PCT = 0.1   # the design space spans ω0 = 2.168-2.203 (1.6 %) in the paper (§3.3.2)

WHY_CALIBRATED = ("the contact parameters were fitted once, at H = 1, on the default ring to three "
                  "targets at once (the paper's ζ_max, its amplitude and the frequency drop there); "
                  "this is the least-squares compromise, seen at the campaign's H (docs/calibration.md)")
WHY_NORMALISED = "equal by construction: ω0 = 2.195 ω / ω_stuck,default"
WHY_OPTIMUM = ("the maximum of ζ_max over the design space of our surrogates (docs/analytics.md): "
               "where the damping of our rings peaks is a prediction of our model, whose free "
               "dimensions and contact parameters are ours")
WHY_SOBOL_LOW = ("at 0.05 mm our rings are stuck or just beginning to slip (the default ring slips "
                 "from about 0.07 mm): ζ there is set by where slip begins, which the three bumps "
                 "move jointly, hence strong interactions and small first-order indices")
WHY_TABLE3 = ("the reduction depends on the amplitude where each ring's damping acts: our optimum is "
              "the optimum of our model and criterion; a level below its slip onset is reduced "
              "little, or amplified if it slips later than the default ring")
WHY_MODEL = ("a prediction of our model: how a bump changes the static contact and the damping "
             "depends on the free dimensions (docs/model.md) and contact parameters, which are ours")


def _row(quantity, paper, ours, unit, scale, source, why, agree_pct=AGREE_PCT):
    """One comparison row; ``why`` is given where ours and the paper's differ by more than
    ``agree_pct`` %."""
    diff = 100 * (ours / paper - 1) if np.isfinite(ours) else np.nan
    verdict = (f"agrees (within {agree_pct:g} %)" if abs(diff) <= agree_pct
               else f"differs: {why}" if np.isfinite(diff) else "not computed")
    return {"quantity": quantity, "paper": paper * scale, "ours": ours * scale, "unit": unit,
            "ours / paper - 1 (%)": diff, "paper source": source, "where ours differ, and why": verdict}


def _ring_rows(label, summary, paper, whys):
    units = {"omega0_low": ("ω0 at the lowest amplitude", "1", 1.0),
             "zeta_max": ("ζ_max", "%", 100.0),
             "q_at_zeta_max": ("|q_res,z| at ζ_max", "mm", 1e3),
             "omega0_at_zeta_max": ("ω0 at ζ_max", "1", 1.0)}
    return [_row(f"{label}: {units[k][0]}", value, summary[k], units[k][1], units[k][2], source,
                 whys[k], AGREE_OMEGA_PCT if k.startswith("omega0") else AGREE_PCT)
            for k, (value, source) in paper.items()]


def paper_comparison(default, case_a, optimum, optimum_kappa, table3: pd.DataFrame,
                     sobol_global=None, max_level=np.inf) -> pd.DataFrame:
    """The comparison table: ``default``, ``case_a`` (κ = (1, 0, 0)) and ``optimum`` are dnnm.nc
    datasets, ``optimum_kappa`` the optimum found by our surrogate, ``table3`` our Table 3 and
    ``sobol_global`` our global Sobol indices (dims output × parameter × level; skipped if None);
    our ζ_max are sought up to |q_res,z| = ``max_level`` [m], the optimum criterion's range."""
    rows = _ring_rows("default ring", dnnm_summary(default, max_level), DEFAULT, {
        "omega0_low": WHY_NORMALISED, "zeta_max": WHY_CALIBRATED, "q_at_zeta_max": WHY_CALIBRATED,
        "omega0_at_zeta_max": WHY_CALIBRATED})
    rows += _ring_rows("case A (1, 0, 0)", dnnm_summary(case_a, max_level), CASE_A,
                       dict.fromkeys(CASE_A, WHY_MODEL))
    paper_k, source = OPTIMUM["kappa"]
    same = np.allclose(optimum_kappa, paper_k)
    rows.append({"quantity": "optimum κ", "paper": str(paper_k), "ours": str(tuple(
        round(float(k), 3) for k in optimum_kappa)), "unit": "1", "ours / paper - 1 (%)": np.nan,
        "paper source": source,
        "where ours differ, and why": "agrees (same corner)" if same else f"differs: {WHY_OPTIMUM}"})
    opt = {k: v for k, v in OPTIMUM.items() if k != "kappa"}
    rows += _ring_rows("optimum ring (computed)", dnnm_summary(optimum, max_level), opt, dict.fromkeys(opt, WHY_MODEL))
    if sobol_global is not None:
        rows += _sobol_rows(sobol_global)
    for i, row in table3.head(len(TABLE3["gamma_N"])).iterrows():   # the paper has four levels
        for key, ours_col, name in (("reduction_pct", "reduction_eebm_pct", "reduction, E-EBM"),
                                    ("reduction_pct", "reduction_frf_pct", "reduction, forced response"),
                                    ("default_mm", "default_eebm_mm", "default amplitude, E-EBM"),
                                    ("optimum_mm", "optimum_eebm_mm", "optimum amplitude, E-EBM")):
            unit = "%" if key == "reduction_pct" else "mm"
            rows.append(_row(f"Table 3 level {i + 1} ({TABLE3['gamma_N'][i]:.0f} N paper, "
                             f"{row.gamma_N:.3g} N ours): {name}", TABLE3[key][i], row[ours_col],
                             unit, 1.0, "§3.4 Table 3",
                             "levels chosen to match by construction" if key == "default_mm"
                             else WHY_TABLE3))
    return pd.DataFrame(rows)


def _sobol_rows(ds) -> list:
    rows = []
    w1 = ds.first_order.sel(output="omega0", parameter="kappa1")
    rows.append(_row("Sobol S1 of ω0 to κ1, lowest over the four amplitude levels", 1.0,
                     float(w1.min()), "1", 1.0, "§3.3.3 (Fig. 18: 'almost reaches 1')", WHY_MODEL))
    zeta = ds.sel(output="zeta").sel(level=SOBOL_LEVEL, method="nearest")
    for kind, values in SOBOL_ZETA.items():
        for k, value in enumerate(values):
            rows.append(_row(f"Sobol {'S1' if kind == 'first_order' else 'ST'} of ζ to κ{k + 1} at "
                             "0.05 mm", value, float(zeta[kind].sel(parameter=f"kappa{k + 1}")),
                             "1", 1.0, SOBOL_SOURCE, WHY_SOBOL_LOW))
    return rows
