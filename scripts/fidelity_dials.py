"""Rule script: the fidelity cases -> results/fidelity/dials.csv (cost, quantities and errors per case)
(ringdamper.studies.fidelity.summary)."""
from ringdamper.io import write_csv
from ringdamper.logs import to_file
from ringdamper.studies.fidelity.summary import case_rows, read_cases

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
cases = read_cases(dict(zip(map(tuple, sm.params.cases), sm.input)))
write_csv(case_rows(sm.params.config, cases), sm.output[0])
