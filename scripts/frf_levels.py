"""Rule script: default ring's dnnm.nc -> the forcing levels whose E-EBM resonant amplitudes are the
configured targets (frf/levels.yaml)."""
from ringdamper.campaign.forced_check import EEBMBackbone, forcing_levels
from ringdamper.io import read_netcdf, write_yaml

sm = snakemake  # noqa: F821 (injected by Snakemake)
targets = sm.config["frf"]["target_amplitudes"]
gamma = forcing_levels(EEBMBackbone.from_dnnm(read_netcdf(sm.input.dnnm, "dnnm")), targets)
write_yaml({"target_amplitudes_m": [float(t) for t in targets],
            "gamma_N": [float(g) for g in gamma]}, sm.output[0])
open(sm.log[0], "w").write(f"targets {targets} m -> gamma {gamma.tolist()} N\n")
