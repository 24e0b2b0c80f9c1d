"""Rule script: kriging.nc + the optimum's computed dnnm.nc -> the surrogate against the computed
backbone at the optimum (table and figure)."""
from ringdamper.campaign.optimum_check import predicted_backbone, surrogate_vs_computed
from ringdamper.campaign.report_tables import write_html_table
from ringdamper.io import read_netcdf
from ringdamper.logs import to_file
from ringdamper.plots.optimum import plot_surrogate_at_optimum

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
computed = read_netcdf(sm.input.dnnm, "dnnm")
predicted = predicted_backbone(read_netcdf(sm.input.kriging), computed.attrs["kappa"])
table = surrogate_vs_computed(predicted, computed, sm.params.config["exploration"]["optimum_max_level"])
table.to_csv(sm.output.csv, index=False, float_format="%.6g")
kappa = ", ".join(f"{k:.4f}" for k in computed.attrs["kappa"])
write_html_table(table, sm.output.html, f"Surrogate against computed backbone at the optimum ({kappa})",
                 notes=["zeta in 1, q_res_z in m, omega0 normalised, gamma in N (SI)."])
plot_surrogate_at_optimum(predicted, computed, sm.output.figure)
log.info("\n%s", table.to_string())
