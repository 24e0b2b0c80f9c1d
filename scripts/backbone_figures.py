"""Rule script: dnnm.nc of the reference rings -> backbones (Figs. 8, 12) and E_d map (Fig. 9b)."""

from ringdamper.io import read_netcdf
from ringdamper.logs import to_file
from ringdamper.plots.dnnm import plot_backbones, plot_energy_map

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
datasets = {label: read_netcdf(path, "dnnm") for label, path in zip(sm.params.labels, sm.input.dnnm)}
plot_backbones(datasets, sm.output.backbones)
plot_energy_map(datasets["default"], read_netcdf(sm.input.default_static, "static"), sm.output.energy)
log.info("rings %s -> %s", list(datasets), list(sm.output))
