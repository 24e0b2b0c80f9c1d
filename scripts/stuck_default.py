"""Rule script: the default ring's reduced.nc + static.nc + resonance.yaml -> stuck_default.yaml
(ringdamper.nonlinear.stage.default_normalisation)."""
import yaml

from ringdamper.io import read_netcdf, write_yaml
from ringdamper.logs import to_file
from ringdamper.nonlinear.stage import default_normalisation

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
with open(sm.input.resonance) as fh:
    target_hz = yaml.safe_load(fh)["frequency_hz"]
normalisation = default_normalisation(read_netcdf(sm.input.reduced, "reduced"), read_netcdf(sm.input.static, "static"),
                                      sm.params.config, target_hz)
write_yaml(normalisation, sm.output[0])
