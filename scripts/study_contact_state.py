"""Rule script: the contact-state search (studies.contact_state) -> its tables and figures:
the search grid (one row per design and ring, one per design), the seven rings' contact maps with
the configured model and with the best design, and the default ring's free closure on each groove
support of the grid (figure, and its mean, axial spread and sector-periodic part in a table)."""
from ringdamper.io import write_csv
from ringdamper.logs import to_file
from ringdamper.plots.static import plot_contact_maps, plot_free_closure, plot_variety_search
from ringdamper.studies.contact_state import (
    best_design,
    configured_design,
    design_states,
    free_closures,
    search,
    sector_half_angle,
    support_label,
)

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
config = sm.params.config
ring_rows, design_rows = search(config)
write_csv(ring_rows, sm.output.rings)
write_csv(design_rows, sm.output.designs)
configured = configured_design(config)
plot_variety_search(design_rows, ring_rows, configured, sm.output.search)
plot_contact_maps(design_states(config, configured), sm.output.maps_configured)
plot_contact_maps(design_states(config, best_design(design_rows, config)), sm.output.maps_best)
closure_rows, closures = free_closures(config)
write_csv(closure_rows, sm.output.closure_table)
plot_free_closure(closures, support_label(configured), sector_half_angle(config), sm.output.closure)
