"""Rule script: one method-limit study (wildcard ``study``) -> its NetCDF and its chart."""
from ringdamper.io import read_netcdf, write_netcdf
from ringdamper.logs import to_file
from ringdamper.studies.method_limits import run

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
dataset = read_netcdf(sm.input[0]) if sm.input else None
write_netcdf(run(sm.wildcards.study, sm.output.png, dataset, sm.params.sizes, sm.params.config["surrogate"]),
             sm.output.nc)
