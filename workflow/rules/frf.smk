# Optimum against default (paper §3.4, Fig. 19, Table 3): forcing levels from the default ring's
# backbone, one forced-response job per ring and level (8 short jobs share the 2 cores), Table 3
# and the figures.
FRF_RINGS = {"default": DEFAULT_GID, "optimum": OPTIMUM_GID}


rule frf_levels:
    input:
        dnnm=f"{RESULTS}/geometry/{DEFAULT_GID}/dnnm.nc",
    output:
        f"{RESULTS}/frf/levels.yaml",
    params:
        config=sections(*FORCED),
    threads: 1
    resources:
        mem_mb=scaled(300),
        runtime=5,
    log:
        log_file("frf/levels"),
    benchmark:
        benchmark_file("frf/levels")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/frf_levels.py"


rule frf_curve:
    input:
        levels=f"{RESULTS}/frf/levels.yaml",
        dnnm=f"{RESULTS}/geometry/{{gid}}/dnnm.nc",
        reduced=f"{RESULTS}/geometry/{{gid}}/reduced.nc",
        static=f"{RESULTS}/geometry/{{gid}}/static.nc",
    output:
        f"{RESULTS}/frf/{{gid}}/gamma_{{level}}.nc",
    wildcard_constraints:
        level=r"\d+",
    params:
        config=sections(*FORCED),
    threads: 1
    resources:
        mem_mb=scaled(1600),
        runtime=5,
    log:
        log_file("frf/{gid}_gamma_{level}"),
    benchmark:
        benchmark_file("frf/{gid}_gamma_{level}")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/frf_curve.py"


rule table3:
    input:
        default=frf_curves(DEFAULT_GID),
        optimum=frf_curves(OPTIMUM_GID),
    output:
        csv=f"{RESULTS}/frf/table3.csv",
        html=report(f"{RESULTS}/tables/table3.html", category="Optimum vs default",
                    caption="../report/table3.rst"),
    threads: 1
    resources:
        mem_mb=scaled(300),
        runtime=5,
    log:
        log_file("frf/table3"),
    benchmark:
        benchmark_file("frf/table3")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/table3.py"


rule optimum_figures:
    input:
        static=[f"{RESULTS}/geometry/{gid}/static.nc" for gid in FRF_RINGS.values()],
        dnnm=[f"{RESULTS}/geometry/{gid}/dnnm.nc" for gid in FRF_RINGS.values()],
        default=frf_curves(DEFAULT_GID),
        optimum=frf_curves(OPTIMUM_GID),
    output:
        maps=report(f"{RESULTS}/figures/optimum_maps.png", category="Optimum vs default",
                    caption="../report/optimum_maps.rst"),
        dynamics=report(f"{RESULTS}/figures/optimum_backbones_frf.png", category="Optimum vs default",
                        caption="../report/optimum_backbones_frf.rst"),
    params:
        labels=list(FRF_RINGS),
    threads: 1
    resources:
        mem_mb=scaled(400),
        runtime=5,
    log:
        log_file("frf/optimum_figures"),
    benchmark:
        benchmark_file("frf/optimum_figures")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/optimum_figures.py"
