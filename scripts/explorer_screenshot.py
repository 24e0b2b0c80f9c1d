"""Rule script: explorer.html + optimum.yaml -> figures/explorer.png, the page at the optimum in headless
chromium (docs/explorer.md)."""
import yaml

from ringdamper.campaign.explorer.screenshot import screenshot
from ringdamper.logs import to_file

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
with open(sm.input.optimum) as fh:
    kappa = yaml.safe_load(fh)["kappa"]
screenshot(sm.input.page, kappa, sm.output[0])
log.info("explorer at the optimum kappa = %s -> %s", kappa, sm.output[0])
