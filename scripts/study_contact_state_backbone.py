"""Rule script: default-ring backbones against the radial clearance (studies.contact_state) ->
table and figure."""
import yaml

from ringdamper.io import write_csv
from ringdamper.logs import to_file
from ringdamper.plots.calibration import plot_backbones
from ringdamper.studies.contact_state import backbone_sweep

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
with open(sm.input.resonance) as fh:
    target_hz = yaml.safe_load(fh)["frequency_hz"]
results = backbone_sweep(sm.params.config, sm.input.reduced, target_hz)
write_csv([row for row, _ in results], sm.output.table)
plot_backbones([(f"c = {1e6 * row['radial_clearance']:g} um, mu {row['friction_coefficient']:g}", curve)
                for row, curve in results], sm.output.figure)
