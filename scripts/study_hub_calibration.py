"""Rule script: configuration -> studies/hub_calibration.yaml (ringdamper.studies.hub_calibration)."""

from ringdamper.io import write_yaml
from ringdamper.logs import to_file
from ringdamper.studies.hub_calibration import study

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
result = study(sm.params.config)
write_yaml(result, sm.output[0])
log.info("%s", result)
