"""Rule script: configuration -> studies/reduction_convergence.csv and .md
(ringdamper.studies.reduction_convergence)."""
from pathlib import Path

from ringdamper.io import write_csv
from ringdamper.logs import to_file
from ringdamper.studies.reduction_convergence import markdown_table, study

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
rows = study(sm.params.config)
write_csv(rows, sm.output.csv)
Path(sm.output.table).write_text(markdown_table(rows) + "\n")
