"""Rule script: the fidelity tables -> summary.yaml (chosen settings, campaign times) and the charts
(ringdamper.studies.fidelity.summary, ringdamper.plots.fidelity)."""
import pandas as pd

from ringdamper.io import write_yaml
from ringdamper.logs import to_file
from ringdamper.plots.fidelity import plot_dials, plot_mesh, plot_pareto
from ringdamper.studies.fidelity.summary import campaign_summary, pareto_points

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
cfg = sm.params.config
dials, mesh, surrogate = (pd.read_csv(p) for p in (sm.input.dials, sm.input.mesh, sm.input.surrogate))
summary = campaign_summary(cfg, dials.to_dict("records"), sm.params.n_geometries, sm.params.n_cores)
write_yaml(summary, sm.output.summary)
plot_dials(dials, summary["chosen"], cfg["fidelity"]["tolerance"], sm.output.dials)
plot_mesh(mesh, cfg["fidelity"]["mesh_families"], sm.output.mesh)
plot_pareto(pareto_points(surrogate, summary["chain_cpu_s"]["current"], sm.params.n_validation, sm.params.n_cores),
            sm.output.pareto)
