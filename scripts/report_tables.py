"""Rule script: the analytics' tables (validation metrics, optimum, Sobol indices) as HTML pages."""
import pandas as pd
import yaml

from ringdamper.campaign.dataset import flagged_truncations
from ringdamper.campaign.report_tables import write_html_table
from ringdamper.io import read_netcdf
from ringdamper.logs import to_file

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
flagged = flagged_truncations(read_netcdf(sm.input.dataset))
write_html_table(pd.read_csv(sm.input.validation), sm.output.validation,
                 "Kriging validation on the held-out geometries",
                 ["Points that keep a lower harmonic truncation (raise over its LU budget or failed; "
                  "truncation_flag in dnnm.nc): " + (f"{len(flagged)} ring(s)" if flagged else "none")] + flagged)
optimum = pd.json_normalize(yaml.safe_load(open(sm.input.optimum)), sep=".").T.reset_index()
optimum.columns = ["key", "value"]
write_html_table(optimum.astype({"value": str}), sm.output.optimum, "Optimum found on the surrogates")
for name in ("sobol_global", "sobol_local"):
    ds = read_netcdf(sm.input[name])
    write_html_table(ds.to_dataframe().reset_index(), sm.output[name],
                     f"Sobol indices ({name.split('_')[1]}): " + ds.attrs.get("domain", ""))
