"""Rule script: config -> results/samples.csv (ringdamper.campaign.sampling)."""
import logging

from ringdamper.campaign.sampling import make_samples
from ringdamper.io import log_to

sm = snakemake  # noqa: F821 (injected by Snakemake)
log_to(sm.log[0])
table = make_samples(sm.config["sampling"])
table.to_csv(sm.output[0], index=False, float_format="%.10g")
logging.getLogger("samples").info("%d samples -> %s", len(table), sm.output[0])
