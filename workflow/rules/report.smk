# Tables of the report and the comparisons that need the surrogates: the Kriging prediction at the
# optimum against its computed backbone, our figures beside the paper's, and the analytics' tables
# (validation metrics, optimum, Sobol indices) as HTML pages the report shows inline.


rule optimum_surrogate_check:
    input:
        kriging=f"{RESULTS}/surrogate/kriging.nc",
        dnnm=f"{RESULTS}/geometry/{OPTIMUM_GID}/dnnm.nc",
    output:
        csv=f"{RESULTS}/surrogate/optimum_check.csv",
        html=report(f"{RESULTS}/tables/optimum_check.html", category="Optimum vs default",
                    caption="../report/optimum_check_table.rst"),
        figure=report(f"{RESULTS}/figures/optimum_surrogate_check.png", category="Optimum vs default",
                      caption="../report/optimum_surrogate_check.rst"),
    params:
        config=sections(*EXPLORATION),
    threads: 1
    resources:
        mem_mb=scaled(400),
        runtime=5,
    log:
        log_file("optimum_surrogate_check"),
    benchmark:
        benchmark_file("optimum_surrogate_check")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/optimum_surrogate_check.py"


rule paper_comparison:
    input:
        default=f"{RESULTS}/geometry/{DEFAULT_GID}/dnnm.nc",
        case_a=f"{RESULTS}/geometry/{reference_gids()['kappa1=+1']}/dnnm.nc",
        optimum=f"{RESULTS}/geometry/{OPTIMUM_GID}/dnnm.nc",
        table3=f"{RESULTS}/frf/table3.csv",
        sobol=f"{RESULTS}/sensitivity/sobol_global.nc",
    output:
        csv=f"{RESULTS}/tables/paper_comparison.csv",
        html=report(f"{RESULTS}/tables/paper_comparison.html", category="Comparison with the paper",
                    caption="../report/paper_comparison.rst"),
    params:
        config=sections(*EXPLORATION, "sensitivity", "frf"),
    threads: 1
    resources:
        mem_mb=scaled(300),
        runtime=5,
    log:
        log_file("paper_comparison"),
    benchmark:
        benchmark_file("paper_comparison")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/paper_comparison.py"


rule report_tables:
    input:
        validation=f"{RESULTS}/surrogate/validation_metrics.csv",
        dataset=f"{RESULTS}/campaign/dataset.nc",
        optimum=f"{RESULTS}/surrogate/optimum.yaml",
        sobol_global=f"{RESULTS}/sensitivity/sobol_global.nc",
        sobol_local=f"{RESULTS}/sensitivity/sobol_local.nc",
    output:
        validation=report(f"{RESULTS}/tables/validation_metrics.html", category="Surrogates",
                          caption="../report/validation_metrics_table.rst"),
        optimum=report(f"{RESULTS}/tables/optimum.html", category="Design space",
                       caption="../report/optimum_table.rst"),
        sobol_global=report(f"{RESULTS}/tables/sobol_global.html", category="Sensitivity",
                            caption="../report/sobol_global_table.rst"),
        sobol_local=report(f"{RESULTS}/tables/sobol_local.html", category="Sensitivity",
                           caption="../report/sobol_local_table.rst"),
    threads: 1
    resources:
        mem_mb=scaled(300),
        runtime=5,
    log:
        log_file("report_tables"),
    benchmark:
        benchmark_file("report_tables")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/report_tables.py"


# The design explorer: one self-contained page evaluating the Kriging models in the browser
# (docs/explorer.md), with the computed rings' backbones and static contact maps.
rule explorer:
    input:
        dataset=f"{RESULTS}/campaign/dataset.nc",
        kriging=f"{RESULTS}/surrogate/kriging.nc",
        optimum=f"{RESULTS}/surrogate/optimum.yaml",
        static=campaign_files("static.nc"),
    output:
        report(f"{RESULTS}/explorer.html", category="Design space", caption="../report/explorer.rst"),
    params:
        config=sections(*EXPLORATION),
        gids=lambda wildcards: campaign_gids(),
    threads: 1
    resources:
        mem_mb=scaled(500),
        runtime=5,
    log:
        log_file("explorer"),
    benchmark:
        benchmark_file("explorer")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/explorer.py"


# A screenshot of the explorer at the optimum (headless chromium; not part of `all`): `make explorer`
# publishes it as docs/figures/explorer.png (docs/artifacts.yaml).
rule explorer_screenshot:
    input:
        page=f"{RESULTS}/explorer.html",
        optimum=f"{RESULTS}/surrogate/optimum.yaml",
    output:
        f"{RESULTS}/figures/explorer.png",
    threads: 1
    resources:
        mem_mb=scaled(1000),
        runtime=5,
    log:
        log_file("explorer_screenshot"),
    benchmark:
        benchmark_file("explorer_screenshot")
    conda:
        "../../envs/ringdamper.yaml"  # the Python side; chromium itself is Debian's (docs/explorer.md)
    script:
        "../../scripts/explorer_screenshot.py"


# The charts of the studies (`make studies`, `make fidelity`: minutes to hours of CPU, not part of
# `all`) that were run into this results folder: `snakemake --report` with the target `study_charts`
# beside `all` (`make report`) shows them; a study not run leaves its charts out, and no study job
# runs for the report (docs/design.md, "The report and the studies' charts").
STUDY_CHARTS = [
    *rules.study_contact_figures.output,
    rules.study_contact_state.output.search,
    rules.study_contact_state_backbone.output.figure,
    rules.study_last_point.output.figure,
    rules.epmc_time_domain.output.figure,
    rules.fidelity_summary.output.dials,
    rules.fidelity_summary.output.mesh,
    rules.fidelity_summary.output.pareto,
    *expand(rules.limits_study.output.png, study=LIMIT_STUDIES),
]


rule study_charts:
    input:
        [chart for chart in STUDY_CHARTS if Path(chart).exists()],
    localrule: True


# The performance page (docs/performance.md, route `performance` of docs/artifacts.yaml): the campaign's
# figures from its tables and job records, and `make bench`'s from results/benchmarks/*.json when present
# (not an input: `make bench` runs outside the workflow). Not part of `all`: `make performance` asks for it.
rule performance_table:
    input:
        row=f"{RESULTS}/tables/design_row.csv",
        samples=f"{RESULTS}/samples.csv",
    output:
        f"{RESULTS}/tables/performance.md",
    params:
        results=lambda wildcards, input: str(Path(input.samples).parent),
    threads: 1
    resources:
        mem_mb=scaled(300),
        runtime=5,
    log:
        log_file("performance_table"),
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/performance_table.py"
