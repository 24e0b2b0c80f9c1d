"""Rule script: default ring -> ND diagram, Campbell diagram, resonance, figures, mode-shape VTUs."""
from pathlib import Path

from ringdamper.io import mesh_fields, read_netcdf, write_netcdf, write_vtu, write_yaml
from ringdamper.logs import to_file
from ringdamper.modal.stage import run_modal_stage, target_mode_shapes
from ringdamper.plots.modal import plot_campbell, plot_mode_shapes, plot_nd_diagram

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
static = read_netcdf(sm.input.static, "static")
if static.attrs["status"] != 0:
    raise RuntimeError(f"the default ring's static solve failed: {static.attrs['reason']}")
res = run_modal_stage(sm.params.config, in_contact=static.in_contact.values.astype(bool))
write_netcdf(res.nd_diagram, sm.output.nd, sm.params.config)
write_netcdf(res.campbell, sm.output.campbell, sm.params.config)
write_yaml(res.resonance, sm.output.resonance)
plot_nd_diagram(res.nd_diagram, sm.output.nd_png)
plot_campbell(res.campbell, res.resonance, sm.output.campbell_png, sm.params.config["geometry"]["n_sectors"])
shapes = target_mode_shapes(res, sm.params.config)
plot_mode_shapes(res.model, shapes, sm.output.modes_png)
points, cells = mesh_fields(res.model)
out = Path(sm.output.modes_vtu)
for j, (freq, family, u) in enumerate(shapes):
    write_vtu(res.model, out / f"mode{j}_{family}.vtu", point_data={**points, "displacement": u},
              cell_data=cells)
log.info("resonance: %s", res.resonance)
