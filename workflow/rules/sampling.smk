rule samples:
    output:
        f"{RESULTS}/samples.csv",
    log:
        f"{RESULTS}/logs/samples.log",
    benchmark:
        f"{RESULTS}/benchmarks/samples.tsv"
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/samples.py"
