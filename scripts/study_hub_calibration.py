"""Rule script: configuration -> studies/hub_calibration.yaml (ringdamper.studies.hub_calibration)."""
import logging

from ringdamper.io import log_to, write_yaml
from ringdamper.studies.hub_calibration import study

sm = snakemake  # noqa: F821 (injected by Snakemake)
log_to(sm.log[0])
result = study(sm.config)
write_yaml(result, sm.output[0])
logging.getLogger("hub_calibration").info("%s", result)
