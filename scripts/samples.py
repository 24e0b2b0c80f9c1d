"""Rule script: config -> results/samples.csv (ringdamper.campaign.sampling)."""

from ringdamper.campaign.sampling import make_samples
from ringdamper.logs import to_file

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
table = make_samples(sm.params.config["sampling"])
table.to_csv(sm.output[0], index=False, float_format="%.10g")
log.info("%d samples -> %s", len(table), sm.output[0])
