# Shared by the rules. The design of experiments is seeded and deterministic, so it is computed at
# parse time: the DAG is static and a dry run lists every job (the `samples` rule writes the same table).
from ringdamper.campaign.sampling import make_samples

SAMPLES = make_samples(config["sampling"]).set_index("gid")


def geometry_ids():
    return list(SAMPLES.index)


def kappa_of(wildcards):
    """kappa of geometry ``gid``."""
    row = SAMPLES.loc[wildcards.gid]
    return [float(row.kappa1), float(row.kappa2), float(row.kappa3)]
