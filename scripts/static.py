"""Rule script: kappa -> static.nc (N0, gap per pair), static.vtu (ringdamper.static.stage) and
mesh.vtu (parts, contact pairs, normals, forcing node) for ParaView, from the one model it builds.

A failed geometry writes static.nc with status 99 and its reason, and both VTU files of its mesh (NaN
static fields); empty VTU files only when no mesh could be built."""

from ringdamper.io import mesh_fields, write_netcdf, write_vtu
from ringdamper.logs import to_file
from ringdamper.reduction.superelement import superelement_path
from ringdamper.static.stage import run_static

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
ds, model, fields = run_static(sm.params.config, sm.params.kappa, superelement_path(sm.input))
if model is None:
    for path in (sm.output.vtu, sm.output.mesh):
        open(path, "w").close()
else:
    write_vtu(model, sm.output.vtu, point_data=fields)
    points, cells = mesh_fields(model)
    write_vtu(model, sm.output.mesh, point_data=points, cell_data=cells)
    log.info("kappa=%s nodes=%d dofs=%d elements=%d pairs=%d", sm.params.kappa,
             len(model.nodes), model.n_dofs, model.geometry.mesh.t.shape[1],
             len(model.pairs))
write_netcdf(ds, sm.output.nc, sm.params.config)
