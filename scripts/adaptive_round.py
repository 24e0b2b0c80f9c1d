"""Rule script (checkpoint): the dnnm.nc of the training rings so far + the earlier rounds' records ->
adaptive/round_<k>.yaml (ringdamper.campaign.adaptive.rounds)."""
import yaml

from ringdamper.campaign.adaptive.rounds import plan_round, training_dataset
from ringdamper.campaign.dataset import kappa
from ringdamper.campaign.sampling import make_samples
from ringdamper.io import write_yaml
from ringdamper.logs import to_file

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
config = sm.params.config
records = []
for path in sm.input.records:
    with open(path) as fh:
        records.append(yaml.safe_load(fh))
samples = make_samples(config["sampling"])
ds, mask = training_dataset(samples, records, dict(zip(sm.params.gids, sm.input.dnnm)))
record = plan_round(ds, mask, records, config, int(sm.wildcards.round), kappa(samples[samples.split == "validation"]),
                    workers=sm.threads)
log.info("round %s: %s", sm.wildcards.round, record)
write_yaml(record, sm.output[0])
