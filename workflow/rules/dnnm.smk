rule stuck_default:
    input:
        reduced=f"{RESULTS}/geometry/{DEFAULT_GID}/reduced.nc",
        static=f"{RESULTS}/geometry/{DEFAULT_GID}/static.nc",
        resonance=f"{RESULTS}/modal/resonance.yaml",
    output:
        f"{RESULTS}/modal/stuck_default.yaml",
    params:
        config=sections(*DNNM),
    threads: 1
    resources:
        mem_mb=scaled(1000),
        runtime=5,
    group:
        f"geometry_{DEFAULT_GID}"
    log:
        log_file("stuck_default"),
    benchmark:
        benchmark_file("stuck_default")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/stuck_default.py"


rule dnnm:
    input:
        reduced=f"{RESULTS}/geometry/{{gid}}/reduced.nc",
        static=f"{RESULTS}/geometry/{{gid}}/static.nc",
        normalisation=f"{RESULTS}/modal/stuck_default.yaml",
        kappa_source=kappa_source,
    output:
        f"{RESULTS}/geometry/{{gid}}/dnnm.nc",
    params:
        config=sections(*DNNM),
        kappa=kappa_of,
    threads: 1
    resources:
        mem_mb=scaled(1000),
        runtime=15,
    group:
        chain_group
    log:
        log_file("dnnm/{gid}"),
    benchmark:
        benchmark_file("dnnm/{gid}")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/dnnm.py"


rule backbone_figures:
    input:
        dnnm=[f"{RESULTS}/geometry/{gid}/dnnm.nc" for gid in reference_gids().values()],
        default_static=f"{RESULTS}/geometry/{DEFAULT_GID}/static.nc",
    output:
        backbones=report(f"{RESULTS}/figures/backbones_reference_rings.png", category="Nonlinear modes",
                         caption="../report/backbones_reference_rings.rst"),
        energy=report(f"{RESULTS}/figures/energy_map_default.png", category="Nonlinear modes",
                      caption="../report/energy_map_default.rst"),
    params:
        labels=list(reference_gids()),
    threads: 1
    resources:
        mem_mb=scaled(600),
        runtime=5,
    log:
        log_file("backbone_figures"),
    benchmark:
        benchmark_file("backbone_figures")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/backbone_figures.py"
