"""Rule script: kappa -> static.nc (N0, gap per pair) and static.vtu (ringdamper.static.stage).

A failed geometry writes static.nc with status 99 and its reason, and static.vtu of its mesh with NaN
fields; an empty static.vtu only when no mesh could be built."""
from ringdamper.io import log_to, write_netcdf, write_vtu
from ringdamper.static.stage import run_static

sm = snakemake  # noqa: F821 (injected by Snakemake)
log_to(sm.log[0])
ds, model, fields = run_static(sm.config, sm.params.kappa)
if model is None:
    open(sm.output.vtu, "w").close()
else:
    write_vtu(model, sm.output.vtu, point_data=fields)
write_netcdf(ds, sm.output.nc, sm.config, sm.rule)
