"""Rule script: static.nc of the default and one-at-a-time rings -> contact maps (Fig. 11)."""

from ringdamper.io import read_netcdf
from ringdamper.logs import to_file
from ringdamper.plots.static import plot_contact_maps

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
plot_contact_maps({label: read_netcdf(path) for label, path in zip(sm.params.labels, sm.input)}, sm.output[0])
log.info("rings %s -> %s", list(sm.params.labels), sm.output[0])
