"""Rule script: the contact calibration's stage CSVs -> tables.md (every trial, Markdown)."""
from pathlib import Path

from ringdamper.logs import to_file
from ringdamper.studies.calibration_tables import calibration_tables

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
Path(sm.output[0]).write_text(calibration_tables(*sm.input), encoding="utf-8")
