rule samples:
    output:
        f"{RESULTS}/samples.csv",
    threads: 1
    resources:
        mem_mb=scaled(400),
        runtime=5,
    log:
        f"{RESULTS}/logs/samples.log",
    benchmark:
        f"{RESULTS}/benchmarks/samples.tsv"
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/samples.py"
