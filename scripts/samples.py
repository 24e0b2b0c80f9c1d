"""Rule script: config -> results/samples.csv."""
from ringdamper.campaign.sampling import make_samples

table = make_samples(snakemake.config["sampling"])  # noqa: F821 (injected by Snakemake)
table.to_csv(snakemake.output[0], index=False, float_format="%.10g")  # noqa: F821
