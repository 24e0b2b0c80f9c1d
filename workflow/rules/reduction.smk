rule reduced:
    input:
        mesh=f"{RESULTS}/geometry/{{gid}}/mesh.vtu",
        static=f"{RESULTS}/geometry/{{gid}}/static.nc",
        kappa_source=kappa_source,
    output:
        f"{RESULTS}/geometry/{{gid}}/reduced.nc",
    params:
        kappa=kappa_of,
    log:
        f"{RESULTS}/logs/reduced/{{gid}}.log",
    benchmark:
        f"{RESULTS}/benchmarks/reduced/{{gid}}.tsv"
    conda:
        "../../envs/fem.yaml"
    script:
        "../../scripts/reduced.py"
