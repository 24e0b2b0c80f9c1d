# Sobol indices of omega0, zeta, gamma at response levels, on the Kriging prediction, the median (paper §3.3.3, §3.4.1).


rule sobol:
    input:
        f"{RESULTS}/surrogate/kriging.nc",
    output:
        sobol_global=f"{RESULTS}/sensitivity/sobol_global.nc",
        sobol_local=f"{RESULTS}/sensitivity/sobol_local.nc",
        csv=report(f"{RESULTS}/sensitivity/sobol_indices.csv", category="Sensitivity",
                   caption="../report/sobol_indices.rst"),
        fig18=report(f"{RESULTS}/figures/fig18_sobol_global.png", category="Sensitivity",
                     caption="../report/fig18_sobol_global.rst"),
        fig20=report(f"{RESULTS}/figures/fig20_sobol_local.png", category="Sensitivity",
                     caption="../report/fig20_sobol_local.rst"),
    params:
        config=sections(*SENSITIVITY),
    threads: 1
    resources:
        mem_mb=scaled(1000),
        runtime=5,
    log:
        log_file("sobol"),
    benchmark:
        benchmark_file("sobol")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/sobol.py"
