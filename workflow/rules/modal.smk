rule modal:
    input:
        static=f"{RESULTS}/geometry/{DEFAULT_GID}/static.nc",
    output:
        nd=f"{RESULTS}/modal/nd_diagram.nc",
        campbell=f"{RESULTS}/modal/campbell.nc",
        resonance=f"{RESULTS}/modal/resonance.yaml",
        nd_png=report(f"{RESULTS}/figures/nd_diagram.png", category="Modal analysis",
                      caption="../report/nd_diagram.rst"),
        campbell_png=report(f"{RESULTS}/figures/campbell.png", category="Modal analysis",
                            caption="../report/campbell.rst"),
        modes_png=report(f"{RESULTS}/figures/modes_target_nd.png", category="Modal analysis",
                         caption="../report/modes_target_nd.rst"),
        modes_vtu=directory(f"{RESULTS}/modal/modes"),
    params:
        config=sections(*MODAL),
    threads: 1
    resources:
        mem_mb=scaled(3000),
        runtime=5,
    group:
        f"geometry_{DEFAULT_GID}"
    log:
        log_file("modal"),
    benchmark:
        benchmark_file("modal")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/modal.py"
