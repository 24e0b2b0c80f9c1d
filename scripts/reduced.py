"""Rule script: kappa -> results/geometry/{gid}/reduced.nc (ringdamper.reduction.stage)."""
from ringdamper.io import write_netcdf
from ringdamper.logs import to_file
from ringdamper.reduction.stage import run_reduced
from ringdamper.reduction.superelement import superelement_path

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
write_netcdf(run_reduced(sm.params.config, sm.params.kappa, superelement_path(sm.input)), sm.output[0],
             sm.params.config)
