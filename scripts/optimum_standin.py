"""DEVELOPMENT STAND-IN rule script (workflow/rules/optimum_standin.smk): optimum.yaml with the
paper's optimum kappa and no surrogate prediction. Deleted with that rule file."""
from ringdamper.io import write_yaml

sm = snakemake  # noqa: F821 (injected by Snakemake)
write_yaml({"kappa": [float(k) for k in sm.params.kappa],
            "criterion": "stand-in: the paper's optimum (section 3.4), not a surrogate result",
            "predicted": {}}, sm.output[0])
open(sm.log[0], "w").write("stand-in optimum.yaml written\n")
