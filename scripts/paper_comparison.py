"""Rule script: our reference rings, optimum, Sobol indices and Table 3 beside the paper's values."""
import pandas as pd

from ringdamper.campaign.paper import paper_comparison
from ringdamper.campaign.report_tables import write_html_table
from ringdamper.io import read_netcdf
from ringdamper.logs import to_file

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
optimum = read_netcdf(sm.input.optimum)
table = paper_comparison(read_netcdf(sm.input.default), read_netcdf(sm.input.case_a), optimum,
                         optimum.attrs["kappa"], pd.read_csv(sm.input.table3),
                         read_netcdf(sm.input.sobol), sm.params.config["exploration"]["optimum_max_level"])
table.to_csv(sm.output.csv, index=False, float_format="%.6g")
write_html_table(table, sm.output.html, "Our campaign beside the paper (Sun et al. 2022)")
log.info("\n%s", table.to_string())
