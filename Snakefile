# ringdamper: the design campaign of friction ring dampers as a Snakemake DAG (docs/design.md §1).
import sys
from pathlib import Path

from ringdamper.config import ConfigError, resolve_imported_mesh, validate_config

configfile: "config.yaml"

report: "workflow/report/workflow.rst"

# a relative imported.mesh is read from the folder of the configuration file that gives it
CONFIG_DIR = Path((list(workflow.overwrite_configfiles) or ["config.yaml"])[-1]).resolve().parent
try:
    resolve_imported_mesh(validate_config(config), CONFIG_DIR)
except ConfigError as err:
    sys.exit(str(err))

RESULTS = config["results"]

include: "workflow/rules/common.smk"
include: "workflow/rules/sampling.smk"
include: "workflow/rules/adaptive.smk"
include: "workflow/rules/modal.smk"
include: "workflow/rules/static.smk"
include: "workflow/rules/reduction.smk"
include: "workflow/rules/dnnm.smk"
include: "workflow/rules/studies.smk"
include: "workflow/rules/surrogate.smk"
include: "workflow/rules/sensitivity.smk"
include: "workflow/rules/frf.smk"
include: "workflow/rules/limits.smk"
include: "workflow/rules/fidelity.smk"
include: "workflow/rules/report.smk"
if config["geometry"].get("source", "builtin") == "imported":

    include: "workflow/rules/imported.smk"


rule all:
    input:
        f"{RESULTS}/samples.csv",
        # the rings known at parse time (the adaptive design's initial and validation rings) by name, so
        # that their jobs are in the DAG from the start and fill the cores while the rounds fit; the
        # input functions below resolve the rounds' rings only once the last round has run
        [f"{RESULTS}/geometry/{gid}/dnnm.nc" for gid in geometry_ids()],
        campaign_files("mesh.vtu"),
        campaign_files("dnnm.nc"),
        f"{RESULTS}/modal/resonance.yaml",
        f"{RESULTS}/figures/static_contact_maps.png",
        f"{RESULTS}/figures/backbones_reference_rings.png",
        f"{RESULTS}/surrogate/validation.nc",
        f"{RESULTS}/figures/fig13_predicted_vs_computed.png",
        f"{RESULTS}/figures/fig13_validation_backbones.png",
        f"{RESULTS}/figures/fig14_kappa1.png",
        f"{RESULTS}/surrogate/optimum.yaml",
        f"{RESULTS}/figures/fig17_envelopes.png",
        f"{RESULTS}/explorer.html",
        f"{RESULTS}/sensitivity/sobol_global.nc",
        f"{RESULTS}/figures/fig18_sobol_global.png",
        f"{RESULTS}/geometry/{OPTIMUM_GID}/dnnm.nc",
        f"{RESULTS}/frf/table3.csv",
        f"{RESULTS}/figures/optimum_maps.png",
        f"{RESULTS}/surrogate/optimum_check.csv",
        f"{RESULTS}/tables/paper_comparison.csv",
        f"{RESULTS}/tables/validation_metrics.html",
        f"{RESULTS}/tables/design_comparison.html",
