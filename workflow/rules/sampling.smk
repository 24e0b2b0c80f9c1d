rule samples:
    input:
        rounds=lambda wildcards: [round_record(r["round"]) for r in finished_rounds()],
    output:
        f"{RESULTS}/samples.csv",
    params:
        config=sections("sampling"),
    threads: 1
    resources:
        mem_mb=scaled(400),
        runtime=5,
    log:
        log_file("samples"),
    benchmark:
        benchmark_file("samples")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/samples.py"
