"""Rule script: campaign/dataset.nc -> surrogate/kriging.nc (one Kriging model per output and amplitude,
fitted on the usable points of the training geometries). The adaptive design's stopping round has fitted
the same models on the same rings: when its models were fitted on exactly these training data and
settings (``fitted_on``), they are taken as they are instead of being fitted again. κ may differ by
KAPPA_DIGITS: samples.csv, which the dataset's κ come from, holds them to 10 significant digits, the
rounds' records (and the rings' own chains) in full."""
from ringdamper.campaign.dataset import check_training, usable_mask
from ringdamper.campaign.kriging import fit_campaign, fitted_on
from ringdamper.io import read_netcdf, write_netcdf
from ringdamper.logs import to_file

KAPPA_DIGITS = 1e-9   # |κ| ≤ 1 written with %.10g

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
settings = sm.params.config["surrogate"]
ds = read_netcdf(sm.input.dataset)
mask = usable_mask(ds)
check_training(ds, mask, settings["min_training"])
train = (ds.split == "training").values
training, training_mask = ds.isel(geometry=train), mask.isel(geometry=train)
stopped = read_netcdf(sm.input.models[0]) if sm.input.models else None   # none for the paper design
if stopped is not None and fitted_on(stopped, training, mask=training_mask, settings=settings,
                                     kappa_tolerance=KAPPA_DIGITS):
    fit = stopped
    log.info("the stopping round's models were fitted on these training data with these settings: taken (%s)",
             sm.input.models[0])
else:
    if stopped is not None:
        log.info("the stopping round's models were fitted on other data or settings: fitting anew")
    fit = fit_campaign(training, mask=training_mask, settings=settings, workers=sm.threads)
log.info("%d models; Q2 per output (median over amplitudes): %s", int((fit.status < 2).sum()),
         {str(o): round(float(fit.q2.sel(output=o).median()), 4) for o in fit.output.values})
write_netcdf(fit, sm.output[0], sm.params.config)
