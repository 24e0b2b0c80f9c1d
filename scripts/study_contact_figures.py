"""Rule script: the contact calibration's backbones -> its two figures."""
from pathlib import Path

from ringdamper.logs import to_file
from ringdamper.studies.contact_calibration import figures

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
figures(sm.params.config, Path(sm.input[0]).parent, sm.output.backbone, sm.output.examples)
