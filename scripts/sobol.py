"""Rule script: kriging.nc -> Sobol indices of omega0, zeta, gamma at the |q_res,z| levels, global on
[-1, 1]^3 (with the polynomial-chaos cross-check) and local on the configured box; Figs. 18 and 20."""
from ringdamper.campaign.kriging import KrigingSurrogate
from ringdamper.campaign.sobol_levels import pce_cross_check, sobol_study, table
from ringdamper.io import read_netcdf, write_netcdf
from ringdamper.logs import to_file
from ringdamper.plots.sensitivity import plot_sobol

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
cfg = sm.params.config["sensitivity"]
surrogate = KrigingSurrogate(read_netcdf(sm.input[0]))
full = [[-1.0, 1.0]] * 3
studies = {"global": pce_cross_check(surrogate, cfg["levels"], full, cfg,
                                     sobol_study(surrogate, cfg["levels"], full, cfg)),
           "local": sobol_study(surrogate, cfg["levels"], cfg["local_box"], cfg)}
for key in ("first_order", "total_order"):
    log.info("global %s: largest |PCE - pick-freeze| %.3g, PCE inside the interval for %.0f %%", key,
             studies["global"].attrs[f"{key}_pce_max_abs_difference"],
             100 * studies["global"].attrs[f"{key}_pce_inside_interval"])
write_netcdf(studies["global"], sm.output.sobol_global, sm.params.config)
write_netcdf(studies["local"], sm.output.sobol_local, sm.params.config)
table(studies).to_csv(sm.output.csv, index=False, float_format="%.5g")
box = " x ".join(f"[{lo:g}, {hi:g}]" for lo, hi in cfg["local_box"])
plot_sobol(studies["global"], sm.output.fig18, "global Sobol indices, kappa in [-1, 1]^3 (paper Fig. 18)")
plot_sobol(studies["local"], sm.output.fig20, f"local Sobol indices, kappa in {box} (paper Fig. 20)")
