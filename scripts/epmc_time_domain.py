"""Rule script: the time-domain check of the rising EPMC frequencies of the Jenkins chain family
(ringdamper.studies.epmc_time_domain; docs/nonlinear_core.md, "Time-domain check of the EPMC"):

1. the frequency rise of every chain of the family -> ``rise``;
2. HBM backbones against time-domain shooting on the two chains with the largest rise and on seed 149
   -> ``comparison`` and the ``figure``;
3. the return errors of seed 179's backbones at H = 3 and 15 -> ``return_179``;
4. the linear viscous analogue of seed 149 -> ``viscous_149``;
5. Δt convergence of the shooting at two points -> ``steps``;
6. the folding chain ``issue_chain`` -> ``issue_chain``.
"""
import pandas as pd

from ringdamper.logs import to_file
from ringdamper.plots.epmc_time_domain import plot_comparison
from ringdamper.studies.epmc_time_domain import (
    issue_chain_check,
    rise_scan,
    spurious_returns,
    step_study,
    viscous_analogue,
    worst_comparisons,
)

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
rise = rise_scan()
rise.to_csv(sm.output.rise, index=False, float_format="%.6g")
tables = worst_comparisons(rise)
pd.concat([t.assign(seed=s) for s, t in tables.items()]).to_csv(
    sm.output.comparison, index=False, float_format="%.8g")
plot_comparison(tables, sm.output.figure)
spurious_returns().to_csv(sm.output.return_179, index=False, float_format="%.6g")
viscous_analogue().to_csv(sm.output.viscous_149, index=False, float_format="%.6g")
step_study().to_csv(sm.output.steps, index=False, float_format="%.10g")
issue_chain_check().to_csv(sm.output.issue_chain, index=False, float_format="%.8g")
