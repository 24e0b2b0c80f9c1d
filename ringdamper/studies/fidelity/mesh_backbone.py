"""Mesh dial on the damper's results: the whole chain on refined meshes.

The mesh levels of :mod:`.mesh` are modal only (frequencies of the stuck target ND). Here the chain
that produces the campaign's results (static contact, reduction, dNNM + E-EBM; :mod:`.chain`) runs
on the campaign's mesh refined by each factor of ``fidelity.mesh_backbone.factors`` (every element
count times the factor, element order kept), for the default ring, at ``n_harmonics`` with
``n_time_samples`` AFT samples. With ``contact_pairs`` (a ``mesh.contact_pairs`` grid) every mesh
carries the same pairs, so the study measures the structure's discretisation alone; without it the
node pairs refine with the mesh (70 → 252 on the 2× 27-node mesh), and a dNNM Newton step's cost
grows with the cube of its 3·pairs·(2H + 1) contact unknowns. The quantities are those of
:mod:`.quantities`, with the forcing levels read on the finest mesh's backbone; errors are relative
to the finest factor.
"""

from __future__ import annotations

import xarray as xr

from ringdamper.studies.mesh_convergence import refined

from .chain import run_case
from .quantities import gamma_at, user_quantities
from .summary import case_summary


def mesh_config(config: dict, factor: int) -> dict:
    """The campaign configuration on the mesh refined by ``factor``, at the study's harmonics (fixed:
    no adaptive truncation) and contact pairs (when it sets them)."""
    settings = config["fidelity"]["mesh_backbone"]
    out = refined(config, factor)          # a deep copy
    out["dnnm"]["n_harmonics"] = out["reduction"]["n_harmonics"] = settings["n_harmonics"]
    out["dnnm"]["max_harmonics"] = settings["n_harmonics"]
    out["dnnm"]["n_time_samples"] = settings["n_time_samples"]
    if "contact_pairs" in settings:
        out["mesh"]["contact_pairs"] = settings["contact_pairs"]
    return out


def mesh_case(config: dict, factor: int, kappa, target_hz: float) -> xr.Dataset:
    """dnnm.nc of ``kappa`` on the mesh refined by ``factor``, with the chain's costs as attributes."""
    ds = run_case(mesh_config(config, factor), kappa, target_hz)
    ds.attrs["factor"] = factor
    return ds


def mesh_rows(config: dict, cases: dict[int, xr.Dataset]) -> list[dict]:
    """One row per refinement factor: pairs, cost, the user quantities and their relative errors
    against the finest factor (``error_max`` the largest)."""
    finest = max(cases)
    levels = config["sensitivity"]["levels"]
    max_level = config["exploration"]["optimum_max_level"]
    gammas = gamma_at(cases[finest], config["frf"]["target_amplitudes"])
    q = {f: user_quantities(ds, levels, gammas, max_level) for f, ds in cases.items()}
    return [{"factor": f, "pairs": cases[f].sizes["pair"], **case_summary(cases[f], q[f], q[finest])}
            for f in sorted(cases)]
