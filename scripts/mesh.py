"""Rule script: kappa -> mesh.vtu (parts, contact pairs, normals, forcing node) for ParaView."""
import logging

from ringdamper.fem.model import build_model
from ringdamper.geometry.sector import build_sector
from ringdamper.io import log_to, mesh_fields, write_vtu

sm = snakemake  # noqa: F821 (injected by Snakemake)
log_to(sm.log[0])
model = build_model(build_sector(sm.config, sm.params.kappa), sm.config)
points, cells = mesh_fields(model)
write_vtu(model, sm.output[0], point_data=points, cell_data=cells)
logging.getLogger("mesh").info("kappa=%s nodes=%d dofs=%d elements=%d pairs=%d", sm.params.kappa,
                               len(model.nodes), model.n_dofs, model.geometry.mesh.t.shape[1],
                               len(model.pairs))
