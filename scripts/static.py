"""Rule script: mesh.vtu + kappa -> static.nc (N0, gap per pair) and static.vtu (fields for ParaView).

The model is rebuilt from kappa and checked against mesh.vtu. Whatever happens, static.nc is written:
a failed solve carries status != 0 and its reason, so the campaign goes on (DESIGN §5).
"""
import traceback

import meshio
import numpy as np
import xarray as xr

from ringdamper.fem.model import build_model
from ringdamper.geometry.sector import build_sector
from ringdamper.io import write_netcdf, write_vtu
from ringdamper.static.stage import solve_static, static_dataset, static_fields

sm = snakemake  # noqa: F821 (injected by Snakemake)
kappa = sm.params.kappa
speed = sm.config["operation"]["speed_rpm"]
with open(sm.log[0], "w") as log:
    try:
        model = build_model(build_sector(sm.config, kappa), sm.config)
        mesh_points = meshio.read(sm.input.mesh).points
        if mesh_points.shape != model.nodes.shape or np.abs(mesh_points - model.nodes).max() > 1e-12:
            raise RuntimeError(f"{sm.input.mesh} does not match the model rebuilt from kappa = {kappa}")
        result, prob = solve_static(model, sm.config)
        ds = static_dataset(model, result, prob, kappa, speed)
        write_vtu(model, sm.output.vtu, point_data=static_fields(model, result, prob))
        log.write(f"status={result.status} ({result.reason}) iterations={result.iterations} "
                  f"in_contact={ds.attrs['n_in_contact']}/{len(model.pairs)} "
                  f"residual={result.residual:.2e} complementarity={result.complementarity:.2e}\n")
    except Exception as err:  # a failed geometry must not stop the campaign
        log.write(traceback.format_exc())
        ds = xr.Dataset(attrs={"kappa": np.asarray(kappa, dtype=float), "speed_rpm": speed,
                               "status": 99, "reason": f"{type(err).__name__}: {err}"})
        open(sm.output.vtu, "w").close()
    write_netcdf(ds, sm.output.nc)
