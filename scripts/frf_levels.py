"""Rule script: default ring's dnnm.nc -> the forcing levels whose E-EBM resonant amplitudes are the
configured targets (frf/levels.yaml)."""
from ringdamper.campaign.forced_check import EEBMBackbone, forcing_levels
from ringdamper.io import read_netcdf, write_yaml
from ringdamper.logs import to_file

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
targets = sm.params.config["frf"]["target_amplitudes"]
gamma = forcing_levels(EEBMBackbone.from_dnnm(read_netcdf(sm.input.dnnm, "dnnm")), targets)
write_yaml({"target_amplitudes_m": [float(t) for t in targets],
            "gamma_N": [float(g) for g in gamma]}, sm.output[0])
log.info("targets %s m -> gamma %s N", targets, gamma.tolist())
