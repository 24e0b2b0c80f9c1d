"""Rule script: the contact-state search (studies.contact_state) -> its tables and figures:
the search grid (one row per design and ring, one per design), the seven rings' contact maps with
the configured model and with the best design, and the default ring's free closure on each arm
thickness (configured length) and each arm length (configured thickness)."""
import numpy as np

from ringdamper.io import log_to, write_csv
from ringdamper.plots.static import plot_contact_maps, plot_free_closure, plot_variety_search
from ringdamper.studies.contact_state import (best_design, design_config, design_states, free_closure, search,
                                              support_of)

sm = snakemake  # noqa: F821 (injected by Snakemake)
log_to(sm.log[0])
config = sm.config
ring_rows, design_rows = search(config)
write_csv(ring_rows, sm.output.rings)
write_csv(design_rows, sm.output.designs)
configured = {"radial_clearance": config["geometry"]["ring"]["radial_clearance"],
              "normal_stiffness_per_area": config["contact"]["normal_stiffness_per_area"], **support_of(config)}
plot_variety_search(design_rows, ring_rows, configured, sm.output.search)
plot_contact_maps(design_states(config, configured), sm.output.maps_configured)
plot_contact_maps(design_states(config, best_design(design_rows, config)), sm.output.maps_best)
grid = config["studies"]["contact_state"]
supports = ([{"arm_thickness": t, "arm_length": configured["arm_length"]} for t in grid["arm_thickness"]]
            + [{"arm_thickness": configured["arm_thickness"], "arm_length": length} for length in grid["arm_length"]])
closures = {f"arm {1e3 * s['arm_thickness']:g} x {1e3 * s['arm_length']:g} mm":
            free_closure(design_config(config, s), grid["free_clearance"]) for s in supports}
plot_free_closure(closures, f"arm {1e3 * configured['arm_thickness']:g} x {1e3 * configured['arm_length']:g} mm",
                  np.pi / config["geometry"]["n_sectors"], sm.output.closure)
