"""Rule script (checkpoint): the dnnm.nc of the training rings so far + the earlier rounds' records ->
adaptive/round_<k>.yaml (ringdamper.campaign.adaptive.rounds) and the round's models,
adaptive/round_<k>_kriging.nc (the kriging rule takes the stopping round's instead of fitting them again)."""
import yaml

from ringdamper.campaign.adaptive.rounds import plan_round, round_models, training_dataset
from ringdamper.campaign.dataset import kappa
from ringdamper.campaign.sampling import make_samples
from ringdamper.io import write_netcdf, write_yaml
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
models = round_models(ds, mask, config, workers=sm.threads)
record = plan_round(ds, mask, records, config, int(sm.wildcards.round), kappa(samples[samples.split == "validation"]),
                    models=models)
log.info("round %s: %s", sm.wildcards.round, record)
write_netcdf(models.kriging, sm.output.models, config)
write_yaml(record, sm.output.record)
