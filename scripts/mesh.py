"""Rule script: kappa -> results/geometry/{gid}/mesh.vtu (parts, contact pairs, normals, forcing node)."""
from ringdamper.fem.model import build_model
from ringdamper.geometry.sector import build_sector
from ringdamper.io import mesh_fields, write_vtu

sm = snakemake  # noqa: F821 (injected by Snakemake)
model = build_model(build_sector(sm.config, sm.params.kappa), sm.config)
points, cells = mesh_fields(model)
write_vtu(model, sm.output[0], point_data=points, cell_data=cells)
with open(sm.log[0], "w") as log:
    log.write(f"kappa={sm.params.kappa} nodes={len(model.nodes)} dofs={model.n_dofs} "
              f"elements={model.geometry.mesh.t.shape[1]} pairs={len(model.pairs)}\n")
