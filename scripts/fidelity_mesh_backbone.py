"""Rule script: the refined meshes' backbones -> results/fidelity/mesh_backbone.csv (cost, quantities
and errors against the finest mesh; ringdamper.studies.fidelity.mesh_backbone)."""
from ringdamper.io import log_to, read_netcdf, write_csv
from ringdamper.studies.fidelity.mesh_backbone import mesh_rows

sm = snakemake  # noqa: F821 (injected by Snakemake)
log_to(sm.log[0])
cases = {int(f): read_netcdf(p) for f, p in zip(sm.params.factors, sm.input)}
write_csv(mesh_rows(sm.config, cases), sm.output[0])
