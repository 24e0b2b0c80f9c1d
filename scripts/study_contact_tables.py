"""Rule script: the contact calibration's stage CSVs -> tables.md (every trial, Markdown)."""
from pathlib import Path

from ringdamper.io import log_to
from ringdamper.studies.calibration_tables import calibration_tables

sm = snakemake  # noqa: F821 (injected by Snakemake)
log_to(sm.log[0])
Path(sm.output[0]).write_text(calibration_tables(*sm.input), encoding="utf-8")
