# DEVELOPMENT STAND-IN, not part of the campaign: the surrogate rules declare the real
# `checkpoint optimum` (the Kriging exploration writes optimum.yaml). This one writes the paper's
# optimum (1, -1, -1) so that the optimum's chain, the forced responses and the report can be
# developed before they exist. Delete this file and its `include:` in the Snakefile when merging.
checkpoint optimum:
    output:
        f"{RESULTS}/surrogate/optimum.yaml",
    params:
        kappa=[1.0, -1.0, -1.0],
    log:
        f"{RESULTS}/logs/optimum.log",
    benchmark:
        f"{RESULTS}/benchmarks/optimum.tsv"
    conda:
        "../../envs/campaign.yaml"
    script:
        "../../scripts/optimum_standin.py"
