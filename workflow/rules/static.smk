# The default ring and the six one-at-a-time extremes of Fig. 11 (label -> gid).
ONE_AT_A_TIME_GIDS = {label: gid_of(k) for label, k in REFERENCE_RINGS.items() if label != "paper optimum"}


rule static:
    input:
        kappa_source=kappa_source,
        superelement=superelement_input,
    output:
        nc=f"{RESULTS}/geometry/{{gid}}/static.nc",
        vtu=f"{RESULTS}/geometry/{{gid}}/static.vtu",
        mesh=f"{RESULTS}/geometry/{{gid}}/mesh.vtu",
    params:
        config=sections(*STATIC),
        kappa=kappa_of,
    threads: 1
    resources:
        mem_mb=scaled(600),
        runtime=5,
    group:
        chain_group
    log:
        log_file("static/{gid}"),
    benchmark:
        benchmark_file("static/{gid}")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/static.py"


rule static_maps:
    input:
        [f"{RESULTS}/geometry/{gid}/static.nc" for gid in ONE_AT_A_TIME_GIDS.values()],
    output:
        report(f"{RESULTS}/figures/static_contact_maps.png", category="Static contact",
               caption="../report/static_contact_maps.rst"),
    params:
        labels=list(ONE_AT_A_TIME_GIDS),
    threads: 1
    resources:
        mem_mb=scaled(600),
        runtime=5,
    log:
        log_file("static_maps"),
    benchmark:
        benchmark_file("static_maps")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/static_maps.py"
