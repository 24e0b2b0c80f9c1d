"""Rule script: Table 3 and the campaign's dnnm.nc / frf curves -> results/fidelity/forced.csv
(E-EBM against forced responses; ringdamper.studies.fidelity.forced)."""
import pandas as pd

from ringdamper.io import write_csv
from ringdamper.logs import to_file
from ringdamper.studies.fidelity.forced import eebm_vs_frf

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
write_csv(eebm_vs_frf(pd.read_csv(sm.input.table3),
                      {"default": sm.input.dnnm_default, "optimum": sm.input.dnnm_optimum},
                      {"default": sm.input.frf_default, "optimum": sm.input.frf_optimum}), sm.output[0])
