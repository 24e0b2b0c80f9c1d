"""Rule script: the mesh levels -> results/fidelity/mesh.csv and mesh_limits.csv (Richardson limits)
(ringdamper.studies.fidelity.mesh)."""
import yaml

from ringdamper.io import write_csv
from ringdamper.logs import to_file
from ringdamper.studies.fidelity.mesh import extrapolate

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
rows = [yaml.safe_load(open(p)) for p in sm.input]
limits = extrapolate(rows, sm.params.config["fidelity"]["mesh_families"])
write_csv(rows, sm.output.levels)
write_csv(limits, sm.output.limits)
