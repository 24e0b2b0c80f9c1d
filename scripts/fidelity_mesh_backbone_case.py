"""Rule script: the default ring's chain on the mesh refined by {factor} ->
results/fidelity/mesh_backbone/{factor}.nc (ringdamper.studies.fidelity.mesh_backbone)."""
import yaml

from ringdamper.io import write_netcdf
from ringdamper.logs import to_file
from ringdamper.studies.fidelity.mesh_backbone import mesh_case

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
with open(sm.input.resonance) as fh:
    target_hz = yaml.safe_load(fh)["frequency_hz"]
write_netcdf(mesh_case(sm.params.config, int(sm.wildcards.factor), (0.0, 0.0, 0.0), target_hz), sm.output[0])
