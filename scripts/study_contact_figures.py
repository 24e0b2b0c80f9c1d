"""Rule script: the contact calibration's backbones -> its two figures."""
from pathlib import Path

from ringdamper.io import log_to
from ringdamper.studies.contact_calibration import figures

sm = snakemake  # noqa: F821 (injected by Snakemake)
log_to(sm.log[0])
figures(sm.config, Path(sm.input[0]).parent, sm.output.backbone, sm.output.examples)
