"""Rule script: the campaign's tables, job records and `make bench`'s files -> the performance page."""
from pathlib import Path

from ringdamper.logs import to_file
from ringdamper.performance import markdown, performance_table

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
Path(sm.output[0]).write_text(markdown(performance_table(sm.params.results)))
