"""Rule script: reduced.nc + static.nc + stuck_default.yaml -> dnnm.nc (ringdamper.nonlinear.stage).

A failed geometry writes dnnm.nc with status 99 and its reason."""
import yaml

from ringdamper.io import read_netcdf, write_netcdf
from ringdamper.logs import to_file
from ringdamper.nonlinear.stage import dnnm_stage

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
with open(sm.input.normalisation) as fh:
    normalisation = yaml.safe_load(fh)
ds = dnnm_stage(read_netcdf(sm.input.reduced, "reduced"), read_netcdf(sm.input.static, "static"), sm.params.config,
                sm.params.kappa, normalisation)
write_netcdf(ds, sm.output[0], sm.params.config)
