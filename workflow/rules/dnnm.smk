rule stuck_default:
    input:
        reduced=f"{RESULTS}/geometry/{DEFAULT_GID}/reduced.nc",
        static=f"{RESULTS}/geometry/{DEFAULT_GID}/static.nc",
        resonance=f"{RESULTS}/modal/resonance.yaml",
    output:
        f"{RESULTS}/modal/stuck_default.yaml",
    threads: 1
    resources:
        mem_mb=scaled(1000),
        runtime=5,
    group:
        f"geometry_{DEFAULT_GID}"
    log:
        f"{RESULTS}/logs/stuck_default.log",
    benchmark:
        f"{RESULTS}/benchmarks/stuck_default.tsv"
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
        kappa=kappa_of,
    threads: 1
    resources:
        mem_mb=scaled(1000),
        runtime=15,
    group:
        "geometry_{gid}"
    log:
        f"{RESULTS}/logs/dnnm/{{gid}}.log",
    benchmark:
        f"{RESULTS}/benchmarks/dnnm/{{gid}}.tsv"
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
        f"{RESULTS}/logs/backbone_figures.log",
    benchmark:
        f"{RESULTS}/benchmarks/backbone_figures.tsv"
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/backbone_figures.py"
