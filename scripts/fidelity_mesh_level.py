"""Rule script: one mesh level (factor, order) -> results/fidelity/mesh/{factor}_{order}.yaml
(ringdamper.studies.fidelity.mesh)."""
from ringdamper.io import write_yaml
from ringdamper.logs import to_file
from ringdamper.studies.fidelity.mesh import mesh_level

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
w = sm.wildcards
write_yaml(mesh_level(sm.params.config, int(w.factor), int(w.order), sm.params.config["fidelity"]["mesh_families"]),
           sm.output[0])
