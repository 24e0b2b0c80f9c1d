"""Rule script: one fidelity case (ring, dial, value) -> results/fidelity/cases/{ring}/{dial}/{value}.nc
(ringdamper.studies.fidelity.chain)."""
import yaml

from ringdamper.io import write_netcdf
from ringdamper.logs import to_file
from ringdamper.studies.fidelity.chain import run_case
from ringdamper.studies.fidelity.dials import case_config, rings

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
with open(sm.input.resonance) as fh:
    target_hz = yaml.safe_load(fh)["frequency_hz"]
w = sm.wildcards
ds = run_case(case_config(sm.params.config, w.dial, w.value), rings(sm.params.config["fidelity"])[w.ring], target_hz)
ds.attrs.update({"ring": w.ring, "dial": w.dial, "value": w.value})
write_netcdf(ds, sm.output[0])
