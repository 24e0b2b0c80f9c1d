"""Rule script: samples.csv, the rounds' records, validation metrics, optimum and its check, the jobs'
benchmarks and CPU records -> the design by round and the stopping trace (figures), the rounds' table
and the design's row of the comparison table beside the other design's committed row."""
from pathlib import Path

import pandas as pd
import yaml

from ringdamper.bench.machine import REFERENCE_ORDER, reference_lu_seconds
from ringdamper.campaign.adaptive.report import comparison_table, design_row, job_times, trace_table
from ringdamper.campaign.design_space import read_samples
from ringdamper.campaign.report_tables import write_html_table
from ringdamper.logs import to_file
from ringdamper.plots.adaptive import plot_design, plot_trace

sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
sampling = sm.params.config["sampling"]
samples = read_samples(sm.input.samples)
records = [yaml.safe_load(open(path)) for path in sm.input.rounds]
trace = trace_table(records)
trace.to_csv(sm.output.rounds, index=False, float_format="%.6g")
write_html_table(trace, sm.output.rounds_html, "Adaptive rounds: estimated validation errors, predicted optimum, stop",
                 notes=["variance_*, loo_*, voronoi_*: estimates of each output's validation RMSE relative to its "
                        "spread over the domain; ratio_*: the stop rule's estimate over sampling.adaptive."
                        "rmse_tolerance (docs/adaptive.md); change_*: largest |delta kappa_i| and relative "
                        "|delta zeta_max| of the optimum since the last round."])
plot_design(samples, sm.output.design)
plot_trace(trace, sm.output.trace)
design = sampling.get("design", "paper")
times = job_times(sm.input.benchmarks, sm.params.cpu_records)
row = design_row(design, samples, records, pd.read_csv(sm.input.metrics, index_col="output"),
                 yaml.safe_load(open(sm.input.optimum)), pd.read_csv(sm.input.check), pd.read_csv(sm.input.table3),
                 times, reference_lu_seconds())
row.to_csv(sm.output.row, index=False, float_format="%.6g")
table, notes = comparison_table(row, Path(sm.params.committed))
if times["sampled_jobs"]:
    notes.append(f"{times['sampled_jobs']} jobs ran before CPU records existed: their CPU is Snakemake's sampled "
                 "cpu_time, a lower bound (docs/adaptive.md).")
if records and records[-1]["reason"] == "budget":
    notes.append(f"The budget sampling.adaptive.n_max = {sampling['adaptive']['n_max']} ran out before the stop "
                 f"rule fired; last worst estimated error over its tolerance {records[-1]['worst_ratio']:.3g}.")
write_html_table(table.T.reset_index().set_axis(["quantity", *table.design], axis=1), sm.output.comparison,
                 "Design comparison on the validation rings",
                 notes=["job_cpu_s, job_wall_s: CPU and wall seconds summed over the chain jobs of every ring and "
                        "the rounds (CPU: each job's own count at exit; wall: Snakemake's benchmarks); "
                        "job_cpu_reference_lus: job_cpu_s in CPU times of a reference LU "
                        f"(reference_lu_s: LAPACK dgetrf of order {REFERENCE_ORDER} on one thread, timed by this "
                        "rule on the machine of the run), the cost to compare between machines (docs/design.md "
                        "section 8); "
                        "*_coverage: share of validation points within +-2 sigma."] + notes)
log.info("\n%s", table.T.to_string())
