"""Rule script: the contact calibration's backbones -> its two figures."""
from pathlib import Path

from ringdamper.logs import to_file
from ringdamper.plots.calibration import plot_backbones
from ringdamper.studies.contact_calibration.dataset import figure_curves

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
backbones, examples = figure_curves(sm.params.config, Path(sm.input[0]).parent)
plot_backbones(backbones, sm.output.backbone)
plot_backbones(examples, sm.output.examples)
