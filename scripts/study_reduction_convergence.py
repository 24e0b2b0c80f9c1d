"""Rule script: configuration -> studies/reduction_convergence.csv and .md
(ringdamper.studies.reduction_convergence)."""
from pathlib import Path

from ringdamper.io import log_to, write_csv
from ringdamper.studies.reduction_convergence import markdown_table, study

sm = snakemake  # noqa: F821 (injected by Snakemake)
log_to(sm.log[0])
rows = study(sm.config)
write_csv(rows, sm.output.csv)
Path(sm.output.table).write_text(markdown_table(rows) + "\n")
