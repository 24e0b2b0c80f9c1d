"""Rule script: campaign/dataset.nc -> results/fidelity/surrogate.csv (Kriging training-set size, LHS
against sequential designs; ringdamper.studies.fidelity.surrogate)."""
from ringdamper.io import read_netcdf, write_csv
from ringdamper.logs import to_file
from ringdamper.studies.fidelity.quantities import gamma_at
from ringdamper.studies.fidelity.surrogate import backbone_dataset, training_size_study

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
cfg = sm.params.config
dataset = read_netcdf(sm.input[0]).load()
d = dataset.sel(geometry=sm.params.default_gid)
gammas = gamma_at(backbone_dataset(dataset.amplitude.values, d.q_res_z.values, d.zeta.values, d.omega0.values,
                                   d.gamma.values, d.status.values), cfg["frf"]["target_amplitudes"])
write_csv(training_size_study(dataset, cfg["fidelity"]["training_sizes"], cfg["surrogate"],
                              cfg["sensitivity"]["levels"], gammas, cfg["exploration"]["optimum_max_level"],
                              cfg["sampling"]["seed"]), sm.output[0])
