# Campaign analytics on the per-geometry dNNMs: dataset, Kriging surrogates, their validation and the
# exploration of the design space (paper §3.2-3.3). The optimum is a checkpoint: rules that need the
# optimum geometry read surrogate/optimum.yaml through checkpoints.optimum.get().


rule aggregate:
    input:
        samples=f"{RESULTS}/samples.csv",
        dnnm=campaign_files("dnnm.nc"),
    output:
        f"{RESULTS}/campaign/dataset.nc",
    params:
        config=sections(*DATASET),
        gids=lambda wildcards: campaign_gids(),
    threads: 1
    resources:
        mem_mb=scaled(400),
        runtime=5,
    log:
        log_file("aggregate"),
    benchmark:
        benchmark_file("aggregate")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/aggregate.py"


rule kriging:
    input:
        dataset=f"{RESULTS}/campaign/dataset.nc",
        models=stopping_round_models,
    output:
        f"{RESULTS}/surrogate/kriging.nc",
    params:
        config=sections(*SURROGATE),
    threads: 2
    resources:
        mem_mb=scaled(1200),
        runtime=10,
    log:
        log_file("kriging"),
    benchmark:
        benchmark_file("kriging")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/kriging.py"


rule validation:
    input:
        dataset=f"{RESULTS}/campaign/dataset.nc",
        kriging=f"{RESULTS}/surrogate/kriging.nc",
    output:
        nc=f"{RESULTS}/surrogate/validation.nc",
        csv=report(f"{RESULTS}/surrogate/validation_metrics.csv", category="Surrogates",
                   caption="../report/validation_metrics.rst"),
        scatter=report(f"{RESULTS}/figures/fig13_predicted_vs_computed.png", category="Surrogates",
                       caption="../report/fig13_predicted_vs_computed.rst"),
        cases=report(f"{RESULTS}/figures/fig13_validation_backbones.png", category="Surrogates",
                     caption="../report/fig13_validation_backbones.rst"),
    params:
        config=sections(*SURROGATE),
    threads: 1
    resources:
        mem_mb=scaled(500),
        runtime=5,
    log:
        log_file("validation"),
    benchmark:
        benchmark_file("validation")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/validation.py"


rule one_at_a_time:
    input:
        dataset=f"{RESULTS}/campaign/dataset.nc",
        kriging=f"{RESULTS}/surrogate/kriging.nc",
    output:
        nc=f"{RESULTS}/surrogate/oat.nc",
        fig14=report(f"{RESULTS}/figures/fig14_kappa1.png", category="Design space",
                     caption="../report/fig14_kappa1.rst"),
        fig15=report(f"{RESULTS}/figures/fig15_kappa2.png", category="Design space",
                     caption="../report/fig15_kappa2.rst"),
        fig16=report(f"{RESULTS}/figures/fig16_kappa3.png", category="Design space",
                     caption="../report/fig16_kappa3.rst"),
    params:
        config=sections(*EXPLORATION),
    threads: 1
    resources:
        mem_mb=scaled(500),
        runtime=5,
    log:
        log_file("one_at_a_time"),
    benchmark:
        benchmark_file("one_at_a_time")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/one_at_a_time.py"


checkpoint optimum:
    input:
        dataset=f"{RESULTS}/campaign/dataset.nc",
        kriging=f"{RESULTS}/surrogate/kriging.nc",
    output:
        optimum=f"{RESULTS}/surrogate/optimum.yaml",
        grid=f"{RESULTS}/surrogate/grid.nc",
        figure=report(f"{RESULTS}/figures/fig17_envelopes.png", category="Design space",
                      caption="../report/fig17_envelopes.rst"),
    params:
        config=sections(*EXPLORATION),
    threads: 1
    resources:
        mem_mb=scaled(800),
        runtime=5,
    log:
        log_file("optimum"),
    benchmark:
        benchmark_file("optimum")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/optimum.py"
