"""Rule script: the default ring's reduced model with the harmonics the studies need ->
results/studies/default_reduced.nc (ringdamper.reduction.stage; the campaign's reduced.nc keeps only
the dNNM's harmonics)."""
import copy

from ringdamper.io import write_netcdf
from ringdamper.logs import to_file
from ringdamper.reduction.stage import run_reduced

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
config = copy.deepcopy(sm.params.config)
config["reduction"]["n_harmonics"] = sm.params.harmonics
write_netcdf(run_reduced(config, (0.0, 0.0, 0.0)), sm.output[0], config)
