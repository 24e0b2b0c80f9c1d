"""Rule script: kappa -> results/geometry/{gid}/reduced.nc (ringdamper.reduction.stage)."""
from ringdamper.io import log_to, write_netcdf
from ringdamper.reduction.stage import run_reduced

sm = snakemake  # noqa: F821 (injected by Snakemake)
log_to(sm.log[0])
write_netcdf(run_reduced(sm.config, sm.params.kappa), sm.output[0], sm.config, sm.rule)
