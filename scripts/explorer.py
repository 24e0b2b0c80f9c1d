"""Rule script: dataset.nc + kriging.nc + optimum.yaml + every static.nc -> explorer.html, the design
explorer page (docs/explorer.md)."""
from ringdamper.campaign.design_space import REFERENCE_RINGS
from ringdamper.campaign.explorer import page_data, write_page
from ringdamper.logs import to_file

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
data = page_data(sm.input.dataset, sm.input.kriging, sm.input.optimum, dict(zip(sm.params.gids, sm.input.static)),
                 REFERENCE_RINGS, sm.params.config["exploration"]["reference_amplitude"])
size = write_page(data, sm.output[0])
log.info("explorer.html: %d models, %d computed rings, %.2f MB", sum(m is not None for ms in data["models"].values()
                                                                    for m in ms), len(data["rings"]), size / 1e6)
