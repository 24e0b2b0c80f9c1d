"""Rule script: the default ring's reduced.nc + resonance.yaml -> one stage of the contact calibration:
studies/contact_calibration/{stage}.csv (one row per trial) and .npz (the backbones).

The trials run in spawned worker processes, which import this file again: the work is guarded by
``__name__ == "__main__"`` so that only the rule's own process runs it."""
import yaml

from ringdamper.io import write_csv
from ringdamper.logs import to_file
from ringdamper.studies.contact_calibration.dataset import run_stage, save_curves

if __name__ == "__main__":
    sm = snakemake  # noqa: F821 (injected by Snakemake)
    log = to_file(sm.log[0])
    with open(sm.input.resonance) as fh:
        target_hz = yaml.safe_load(fh)["frequency_hz"]
    results = run_stage(sm.params.config, sm.input.reduced, target_hz, sm.wildcards.stage, sm.threads)
    write_csv([row for row, _ in results], sm.output.table)
    save_curves(results, sm.output.curves)
