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


# The charts of the fidelity study, the method-limit studies, the last-point analysis and the EPMC's
# time-domain check are measured by `make fidelity`, `make studies` and `python -m
# tools.epmc_time_domain` (minutes to hours of CPU, not part of the campaign) and committed under
# docs/figures/; the report shows the committed charts beside the campaign's own figures.
STUDY_CHARTS = ("fidelity_dials", "fidelity_mesh", "fidelity_pareto", "method_limits_eebm_validity",
                "method_limits_harmonics", "method_limits_kriging_coverage", "method_limits_stability",
                "last_point_separation", "epmc_time_domain")


rule study_charts:
    input:
        **{name: f"docs/figures/{name}.png" for name in STUDY_CHARTS},
    output:
        **{name: report(f"{RESULTS}/figures/studies/{name}.png", category="Fidelity and method limits",
                        caption=f"../report/{name}.rst") for name in STUDY_CHARTS},
    localrule: True
    log:
        log_file("study_charts"),
    params:
        folder=lambda wildcards, output: Path(output[0]).parent,
    conda:
        "../../envs/ringdamper.yaml"
    shell:
        "cp -v {input:q} {params.folder:q} > {log:q} 2>&1"
