"""Rule script: the imported sector -> checks, counts, mass, blisk ND frequencies at rest and at speed."""
import csv

from ringdamper.imported.report import nd_frequencies, summary
from ringdamper.imported.sector import load_imported_sector
from ringdamper.io import provenance, write_yaml
from ringdamper.logs import to_file

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
cfg = sm.params.config
sector = load_imported_sector(cfg["imported"], cfg["material"])
report = summary(sector)
log.info("imported sector: %s", report)
rows = nd_frequencies(sector, [0.0, cfg["operation"]["speed_rpm"]], cfg["modal"]["n_modes"])
with open(sm.output.nd, "w", newline="") as fh:
    writer = csv.DictWriter(fh, fieldnames=["nd", "mode", "speed_rpm", "frequency_hz"])
    writer.writeheader()
    writer.writerows({**r, "frequency_hz": f"{r['frequency_hz']:.10g}"} for r in rows)
write_yaml({**report, "speeds_rpm": [0.0, cfg["operation"]["speed_rpm"]], "provenance": provenance(cfg)},
           sm.output.report)
