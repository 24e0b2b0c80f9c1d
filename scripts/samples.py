"""Rule script: config (+ the adaptive rounds' records) -> results/samples.csv: the design known before
any job (ringdamper.campaign.sampling) followed by the rings the rounds chose."""
import yaml

from ringdamper.campaign.adaptive.design import with_rounds
from ringdamper.campaign.sampling import make_samples
from ringdamper.logs import to_file

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
records = []
for path in sm.input.rounds:
    with open(path) as fh:
        records.append(yaml.safe_load(fh))
table = make_samples(sm.params.config["sampling"])
if records:
    table = with_rounds(table, records)
table.to_csv(sm.output[0], index=False, float_format="%.10g")
log.info("%d samples (%d chosen by %d rounds) -> %s", len(table), sum(len(r["chosen"]) for r in records),
         len(records), sm.output[0])
