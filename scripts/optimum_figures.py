"""Rule script: static.nc, dnnm.nc and forced responses of the default and optimum rings ->
Fig. 19 (maps; backbones and forced responses)."""
from ringdamper.io import read_netcdf
from ringdamper.logs import to_file
from ringdamper.plots.optimum import plot_optimum_dynamics, plot_optimum_maps

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
labels = sm.params.labels
statics = {ring: read_netcdf(p, "static") for ring, p in zip(labels, sm.input.static)}
dnnms = {ring: read_netcdf(p, "dnnm") for ring, p in zip(labels, sm.input.dnnm)}
curves = {ring: [read_netcdf(p) for p in sm.input[ring]] for ring in labels}
plot_optimum_maps(statics, dnnms, curves, sm.output.maps)
plot_optimum_dynamics(dnnms, curves, sm.output.dynamics)
