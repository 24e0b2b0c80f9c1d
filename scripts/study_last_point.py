"""Rule script: the default ring's backbone at the top of the amplitude grid, campaign trace and fine
trace with the normal-force ratio (studies.last_point) -> two NetCDF files and the figure."""

import yaml

from ringdamper.io import read_netcdf, write_netcdf
from ringdamper.logs import to_file
from ringdamper.plots.last_point import plot_separation
from ringdamper.studies.last_point import onset_of_separation, run_study

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
with open(sm.input.resonance) as fh:
    target_hz = yaml.safe_load(fh)["frequency_hz"]
traces = run_study(read_netcdf(sm.input.reduced, "reduced"), read_netcdf(sm.input.static, "static"),
                   sm.params.config, target_hz)
for name, ds in traces.items():
    write_netcdf(ds, sm.output[name], sm.params.config)
    log.info("%s trace: first pair lifts off at alpha = %.4g", name, onset_of_separation(ds))
plot_separation(traces, onset_of_separation(traces["fine"]), sm.output.figure)
