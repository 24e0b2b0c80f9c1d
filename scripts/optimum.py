"""Rule script (checkpoint): kriging.nc -> the 50^3 grid exploration (surrogate/grid.nc, Fig. 17)
and the optimum geometry (surrogate/optimum.yaml)."""
import numpy as np

from ringdamper.campaign.dataset import usable_mask
from ringdamper.campaign.exploration import (
                                             cube_grid,
                                             explore_grid,
                                             find_optimum,
                                             forcing_of,
                                             grid_dataset,
                                             optimum_record,
                                             response_axis,
)
from ringdamper.campaign.kriging import KrigingSurrogate
from ringdamper.io import read_netcdf, write_netcdf, write_yaml
from ringdamper.logs import to_file
from ringdamper.plots.surrogate import plot_envelopes

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
cfg = sm.params.config["exploration"]
ds = read_netcdf(sm.input.dataset)
surrogate = KrigingSurrogate(read_netcdf(sm.input.kriging))
levels = response_axis(ds, usable_mask(ds), cfg["n_levels"])
forcing = forcing_of(surrogate, np.zeros(3), cfg["reference_amplitude"])
grid = explore_grid(surrogate, cube_grid(cfg["grid_points"]), levels, forcing, cfg["optimum_max_level"])
log.info("%d grid geometries, %d predicted |q_res,z|(alpha) not increasing", len(grid.X), grid.n_non_monotone)
optimum = find_optimum(surrogate, grid, forcing, cfg["grid_points"], cfg["optimum_max_level"])
record = optimum_record(surrogate, grid, optimum, forcing, cfg)
log.info("optimum: %s", record)
write_yaml(record, sm.output.optimum)
grid_ds = grid_dataset(surrogate, grid, optimum, cfg["grid_points"])
write_netcdf(grid_ds, sm.output.grid, sm.params.config)
plot_envelopes(grid_ds, sm.output.figure)
