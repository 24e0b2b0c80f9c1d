"""Rule script: campaign/dataset.nc -> surrogate/kriging.nc (one Kriging model per output and amplitude,
fitted on the usable points of the training geometries)."""
from ringdamper.campaign.dataset import check_training, usable_mask
from ringdamper.campaign.kriging import fit_campaign
from ringdamper.io import read_netcdf, write_netcdf
from ringdamper.logs import to_file

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
settings = sm.params.config["surrogate"]
ds = read_netcdf(sm.input[0])
mask = usable_mask(ds)
check_training(ds, mask, settings["min_training"])
train = (ds.split == "training").values
fit = fit_campaign(ds.isel(geometry=train), mask=mask.isel(geometry=train), settings=settings,
                   workers=sm.threads)
log.info("fitted %d models; Q2 per output (median over amplitudes): %s", int((fit.status < 2).sum()),
         {str(o): round(float(fit.q2.sel(output=o).median()), 4) for o in fit.output.values})
write_netcdf(fit, sm.output[0], sm.params.config)
