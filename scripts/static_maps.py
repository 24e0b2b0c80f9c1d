"""Rule script: static.nc of the default and one-at-a-time rings -> contact maps (Fig. 11)."""
from ringdamper.io import read_netcdf
from ringdamper.plots.static import plot_contact_maps

sm = snakemake  # noqa: F821 (injected by Snakemake)
plot_contact_maps({label: read_netcdf(path) for label, path in zip(sm.params.labels, sm.input)}, sm.output[0])
open(sm.log[0], "w").close()
