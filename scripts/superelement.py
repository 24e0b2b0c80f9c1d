"""Rule script: the campaign's fixed substructure -> results/superelement/fixed_part.npz
(ringdamper.reduction.superelement), built once and read by every ring's static and reduced jobs.

``params.config`` holds what the fixed part depends on (its rerun trigger); meshing the sector also
needs the ring's radial thickness, which moves only the ring: it is read from the workflow's
configuration, and every ring checks the fixed part's nodes against the file."""
import copy

from ringdamper.logs import to_file
from ringdamper.reduction.superelement import build_superelement, save

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
config = copy.deepcopy(sm.params.config)
config["geometry"]["ring"] = {**sm.config["geometry"]["ring"], **config["geometry"]["ring"]}
se = build_superelement(config)
save(se, sm.output[0])
log.info("super-element: %d boundary DoFs, harmonics %s, CPU %s", len(se.boundary),
         se.harmonics.tolist(), {k: round(v, 2) for k, v in se.cpu_s.items()})
