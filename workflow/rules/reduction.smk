from ringdamper.reduction.superelement import blisk_config


rule superelement:
    output:
        SUPERELEMENT,
    params:
        config=blisk_config(config),
    threads: 1
    resources:
        mem_mb=scaled(1000),
        runtime=10,
    log:
        log_file("superelement"),
    benchmark:
        benchmark_file("superelement")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/superelement.py"


rule reduced:
    input:
        kappa_source=kappa_source,
        superelement=superelement_input,
    output:
        f"{RESULTS}/geometry/{{gid}}/reduced.nc",
    params:
        config=sections(*REDUCED),
        kappa=kappa_of,
    threads: 1
    resources:
        mem_mb=scaled(1000),
        runtime=5,
    group:
        chain_group
    log:
        log_file("reduced/{gid}"),
    benchmark:
        benchmark_file("reduced/{gid}")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/reduced.py"
