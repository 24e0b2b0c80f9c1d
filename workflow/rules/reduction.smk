rule reduced:
    input:
        kappa_source=kappa_source,
    output:
        f"{RESULTS}/geometry/{{gid}}/reduced.nc",
    params:
        kappa=kappa_of,
    threads: 1
    resources:
        mem_mb=scaled(1000),
        runtime=5,
    group:
        "geometry_{gid}"
    log:
        f"{RESULTS}/logs/reduced/{{gid}}.log",
    benchmark:
        f"{RESULTS}/benchmarks/reduced/{{gid}}.tsv"
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/reduced.py"
