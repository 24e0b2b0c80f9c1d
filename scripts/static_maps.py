"""Rule script: static.nc of the default and one-at-a-time rings -> contact maps (Fig. 11)."""
import logging

from ringdamper.io import log_to, read_netcdf
from ringdamper.plots.static import plot_contact_maps

sm = snakemake  # noqa: F821 (injected by Snakemake)
log_to(sm.log[0])
plot_contact_maps({label: read_netcdf(path) for label, path in zip(sm.params.labels, sm.input)}, sm.output[0])
logging.getLogger("static_maps").info("rings %s -> %s", list(sm.params.labels), sm.output[0])
