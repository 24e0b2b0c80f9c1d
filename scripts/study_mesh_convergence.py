"""Rule script: configuration -> studies/mesh_convergence.csv (ringdamper.studies.mesh_convergence)."""
from ringdamper.io import log_to, write_csv
from ringdamper.studies.mesh_convergence import mesh_study

sm = snakemake  # noqa: F821 (injected by Snakemake)
log_to(sm.log[0])
write_csv(mesh_study(sm.config, sm.config["studies"]["mesh_convergence"]["levels"]), sm.output[0])
