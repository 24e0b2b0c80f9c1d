"""Rule script: the refined meshes' backbones -> results/fidelity/mesh_backbone.csv (cost, quantities
and errors against the finest mesh; ringdamper.studies.fidelity.mesh_backbone)."""
from ringdamper.io import read_netcdf, write_csv
from ringdamper.logs import to_file
from ringdamper.studies.fidelity.mesh_backbone import mesh_rows

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
cases = {int(f): read_netcdf(p) for f, p in zip(sm.params.factors, sm.input)}
write_csv(mesh_rows(sm.params.config, cases), sm.output[0])
