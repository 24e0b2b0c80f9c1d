"""Rule script: the contact-state search (studies.contact_state) -> its tables and figures:
the search grid (one row per design and ring, one per design), the seven rings' contact maps with
the configured model and with the best design, and the default ring's free closure on each groove
support of the grid (figure, and its mean, axial spread and sector-periodic part in a table)."""
import itertools

import numpy as np

from ringdamper.io import write_csv
from ringdamper.logs import to_file
from ringdamper.plots.static import plot_contact_maps, plot_free_closure, plot_variety_search
from ringdamper.studies.contact_state import (
                                              best_design,
                                              closure_summary,
                                              design_config,
                                              design_states,
                                              free_closure,
                                              search,
                                              support_of,
)

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
config = sm.params.config
ring_rows, design_rows = search(config)
write_csv(ring_rows, sm.output.rings)
write_csv(design_rows, sm.output.designs)
configured = {"radial_clearance": config["geometry"]["ring"]["radial_clearance"],
              "normal_stiffness_per_area": config["contact"]["normal_stiffness_per_area"], **support_of(config)}
plot_variety_search(design_rows, ring_rows, configured, sm.output.search)
plot_contact_maps(design_states(config, configured), sm.output.maps_configured)
plot_contact_maps(design_states(config, best_design(design_rows, config)), sm.output.maps_best)
grid = config["studies"]["contact_state"]
half_angle = np.pi / config["geometry"]["n_sectors"]
supports = [{"arm_thickness": t, "arm_length": length}
            for t, length in itertools.product(grid["arm_thickness"], grid["arm_length"])]
supports += [support_of(config)] * (support_of(config) not in supports)   # the configured one is charted
closures = {f"arm {1e3 * s['arm_thickness']:g} x {1e3 * s['arm_length']:g} mm":
            (s, free_closure(design_config(config, s), grid["free_clearance"])) for s in supports}
write_csv([{**s, **closure_summary(state, half_angle)} for s, (state, _) in closures.values()],
          sm.output.closure_table)
plot_free_closure({label: c for label, (_, c) in closures.items()},
                  f"arm {1e3 * configured['arm_thickness']:g} x {1e3 * configured['arm_length']:g} mm",
                  half_angle, sm.output.closure)
