"""Rule script: kriging.nc -> surrogate/oat.nc and Figs. 14-16 (one-at-a-time sweeps of kappa1..3)."""
from ringdamper.campaign.dataset import usable_mask
from ringdamper.campaign.exploration import response_axis, sweeps
from ringdamper.campaign.kriging import KrigingSurrogate
from ringdamper.io import read_netcdf, write_netcdf
from ringdamper.logs import to_file
from ringdamper.plots.surrogate import plot_one_at_a_time

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
cfg = sm.params.config["exploration"]
ds = read_netcdf(sm.input.dataset)
levels = response_axis(ds, usable_mask(ds), cfg["n_levels"])
oat = sweeps(KrigingSurrogate(read_netcdf(sm.input.kriging)), cfg["oat_points"], levels)
write_netcdf(oat, sm.output.nc, sm.params.config)
for i, path in enumerate([sm.output.fig14, sm.output.fig15, sm.output.fig16]):
    plot_one_at_a_time(oat, i, path)
