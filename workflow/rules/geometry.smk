rule mesh:
    input:
        kappa_source,
    output:
        f"{RESULTS}/geometry/{{gid}}/mesh.vtu",
    params:
        kappa=kappa_of,
    threads: 1
    resources:
        mem_mb=scaled(500),
        runtime=5,
    group:
        "geometry_{gid}"
    log:
        f"{RESULTS}/logs/mesh/{{gid}}.log",
    benchmark:
        f"{RESULTS}/benchmarks/mesh/{{gid}}.tsv"
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/mesh.py"
