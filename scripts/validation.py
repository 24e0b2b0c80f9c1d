"""Rule script: dataset.nc + kriging.nc -> surrogate/validation.nc, the metrics table and Fig. 13."""
from ringdamper.campaign.dataset import flagged_truncations, usable_mask
from ringdamper.campaign.kriging import KrigingSurrogate
from ringdamper.campaign.validation import metrics_table, named_gids, validate
from ringdamper.io import read_netcdf, write_netcdf
from ringdamper.logs import to_file
from ringdamper.plots.surrogate import plot_predicted_vs_computed, plot_validation_cases

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
ds = read_netcdf(sm.input.dataset)
fit = read_netcdf(sm.input.kriging)
val = validate(fit, KrigingSurrogate(fit), ds, usable_mask(ds))
write_netcdf(val, sm.output.nc, sm.params.config)
table = metrics_table(val)
table.to_csv(sm.output.csv, float_format="%.6g")
log.info("validation metrics:\n%s", table.to_string())
for line in flagged_truncations(ds):
    log.warning("harmonic truncation flagged: %s", line)
plot_predicted_vs_computed(val, sm.output.scatter)
plot_validation_cases(val, named_gids(val, sm.params.config["sampling"]["named_validation"]), sm.output.cases)
