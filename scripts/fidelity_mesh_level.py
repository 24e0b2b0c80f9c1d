"""Rule script: one mesh level (factor, order) -> results/fidelity/mesh/{factor}_{order}.yaml
(ringdamper.studies.fidelity.mesh)."""
from ringdamper.io import log_to, write_yaml
from ringdamper.studies.fidelity.mesh import mesh_level

sm = snakemake  # noqa: F821 (injected by Snakemake)
log_to(sm.log[0])
w = sm.wildcards
write_yaml(mesh_level(sm.config, int(w.factor), int(w.order), sm.config["fidelity"]["mesh_families"]),
           sm.output[0])
