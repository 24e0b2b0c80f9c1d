"""Rule script: samples.csv + every dnnm.nc -> campaign/dataset.nc (geometry x amplitude)."""
from ringdamper.campaign.dataset import aggregate, status_summary
from ringdamper.campaign.design_space import read_samples
from ringdamper.io import write_netcdf
from ringdamper.logs import to_file

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
samples = read_samples(sm.input.samples)
missing = sorted(set(samples.gid) - set(sm.params.gids))
if missing:
    # Snakemake resolved this job's inputs from round records that a rerun round then rewrote
    # (docs/adaptive.md, "In Snakemake"): the rings are computed, the next run aggregates them.
    raise SystemExit(f"samples.csv lists rings this job was not given: {missing}. An adaptive round "
                     "reran in this run and chose other rings; run the campaign again (make campaign) "
                     "to aggregate them: nothing finished is recomputed.")
ds = aggregate(samples, dict(zip(sm.params.gids, sm.input.dnnm)))
for split in ("training", "validation", "reference"):
    status = ds.status.values[(ds.split == split).values]
    log.info("%s: %d geometries, points %s", split, len(status), status_summary(status.ravel()))
write_netcdf(ds, sm.output[0], sm.params.config)
