"""Rule script: one method-limit study (wildcard ``study``) -> its NetCDF and its chart."""
from ringdamper.io import read_netcdf, write_netcdf
from ringdamper.logs import to_file
from ringdamper.plots.method_limits import plot_eebm_validity, plot_harmonics, plot_kriging_coverage, plot_stability
from ringdamper.studies.method_limits import run
from ringdamper.studies.method_limits.harmonics import worst_error

CHARTS = {"eebm_validity": plot_eebm_validity,
          "harmonics": lambda ds, png: plot_harmonics(ds, worst_error(ds), png),
          "stability": plot_stability,
          "kriging_coverage": plot_kriging_coverage}

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
dataset = read_netcdf(sm.input[0]) if sm.input else None
study = run(sm.wildcards.study, dataset, sm.params.sizes, sm.params.config["surrogate"])
CHARTS[sm.wildcards.study](study, sm.output.png)
write_netcdf(study, sm.output.nc)
