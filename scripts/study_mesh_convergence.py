"""Rule script: configuration -> studies/mesh_convergence.csv (ringdamper.studies.mesh_convergence)."""
from ringdamper.io import write_csv
from ringdamper.logs import to_file
from ringdamper.studies.mesh_convergence import mesh_study

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
write_csv(mesh_study(sm.params.config, sm.params.config["studies"]["mesh_convergence"]["levels"]), sm.output[0])
