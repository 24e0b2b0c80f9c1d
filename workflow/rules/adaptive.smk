# The adaptive design's rounds (docs/adaptive.md). Round k is a checkpoint: it reads the dnnm.nc of the
# training rings computed so far (the initial design's and those rounds 1 .. k-1 chose), fits the
# surrogates, and writes its record: the stop decision and, unless it stops, the rings of round k
# (gids a<k>_<i>), which then run through the same per-geometry rules as every other ring. It also writes
# its models, which the rule kriging takes from the round that stopped (same rings, same fit). While a round
# fits or its rings wait, the validation rings and the modal stage keep the cores busy.


checkpoint adaptive_round:
    input:
        dnnm=lambda wildcards: [f"{RESULTS}/geometry/{gid}/dnnm.nc" for gid in round_training(wildcards)],
        records=lambda wildcards: [round_record(k) for k in range(1, int(wildcards.round))],
    output:
        record=round_record("{round}"),
        models=round_models("{round}"),
    wildcard_constraints:
        round=r"[1-9][0-9]*",
    params:
        config=sections(*EXPLORATION),
        gids=round_training,
    threads: 2
    resources:
        mem_mb=scaled(1200),
        runtime=10,
    log:
        log_file("adaptive/round_{round}"),
    benchmark:
        benchmark_file("adaptive/round_{round}")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/adaptive_round.py"


# The design in the report: its rings by round, the stopping trace, and its row of the comparison table
# beside the other design's committed row (docs/adaptive/, written by this rule on a run of that design).
rule adaptive_report:
    input:
        samples=f"{RESULTS}/samples.csv",
        rounds=lambda wildcards: [round_record(r["round"]) for r in finished_rounds()],
        metrics=f"{RESULTS}/surrogate/validation_metrics.csv",
        optimum=f"{RESULTS}/surrogate/optimum.yaml",
        check=f"{RESULTS}/surrogate/optimum_check.csv",
        table3=f"{RESULTS}/frf/table3.csv",
        benchmarks=chain_benchmarks,
    output:
        design=report(f"{RESULTS}/figures/design_by_round.png", category="Design of experiments",
                      caption="../report/design_by_round.rst"),
        trace=report(f"{RESULTS}/figures/stopping_trace.png", category="Design of experiments",
                     caption="../report/stopping_trace.rst"),
        rounds=f"{RESULTS}/tables/adaptive_rounds.csv",
        rounds_html=report(f"{RESULTS}/tables/adaptive_rounds.html", category="Design of experiments",
                           caption="../report/adaptive_rounds.rst"),
        row=f"{RESULTS}/tables/design_row.csv",
        comparison=report(f"{RESULTS}/tables/design_comparison.html", category="Design of experiments",
                          caption="../report/design_comparison.rst"),
    params:
        config=sections(*EXPLORATION),
        committed=DESIGN_ROW.format(design=OTHER_DESIGN),
        cpu_records=chain_cpu_records,
    threads: 1
    resources:
        mem_mb=scaled(400),
        runtime=5,
    log:
        log_file("adaptive_report"),
    benchmark:
        benchmark_file("adaptive_report")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/adaptive_report.py"
