"""Rule script: one forced-response curve of geometry {gid} at forcing level {level}, with its peak
and the E-EBM prediction from the geometry's backbone (frf/{gid}/gamma_{level}.nc)."""
import yaml

from ringdamper.campaign.forced_check import EEBMBackbone, forced_curve
from ringdamper.io import read_netcdf, write_netcdf
from ringdamper.logs import to_file
from ringdamper.nonlinear.stage import contacts_from_static, structure_from_reduced

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
cfg = sm.params.config
gamma = yaml.safe_load(open(sm.input.levels))["gamma_N"][int(sm.wildcards.level) - 1]
dnnm = read_netcdf(sm.input.dnnm, "dnnm")
H, nt = int(dnnm.attrs["n_harmonics"]), int(dnnm.attrs["n_time_samples"])
ds = forced_curve(structure_from_reduced(read_netcdf(sm.input.reduced, "reduced"), H),
                  contacts_from_static(read_netcdf(sm.input.static, "static"), cfg["contact"],
                                       dnnm.attrs["friction_law"]),
                  EEBMBackbone.from_dnnm(dnnm), gamma, H=H, nt=nt,
                  zeta_s=float(dnnm.attrs["structural_damping_ratio"]),
                  band=cfg["frf"]["frequency_band"],
                  omega_reference=float(dnnm.attrs["omega_stuck_default"]))
ds.attrs.update(gid=sm.wildcards.gid, level=int(sm.wildcards.level), kappa=dnnm.attrs["kappa"])
write_netcdf(ds, sm.output[0], sm.params.config)
log.info("gamma %.6g N: %d points, status %d (%s), peak %.5f mm vs E-EBM %.5f mm, wall %.2f s", gamma,
         ds.sizes["point"], int(ds.status), ds.attrs["reason"], 1e3 * float(ds.peak_amplitude),
         1e3 * float(ds.eebm_amplitude), ds.attrs["wall_time_s"])
