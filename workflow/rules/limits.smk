# Where the methods fail (docs/method_limits.md): `snakemake method_limits` -> results/fidelity/limits/.
# Not part of the default campaign. The E-EBM, harmonic-truncation and stability studies run on small
# analytic systems; the Kriging coverage study refits the surrogates of the campaign dataset.
# Resources (common.smk's convention) from one run of each on the shared 2-core machine: the largest,
# Kriging coverage, 271 s and 309 MB (E-EBM 176 s and 173 MB, harmonics 13 s, stability 11 s).
from ringdamper.studies.method_limits import STUDIES as LIMIT_STUDIES

LIMITS = f"{RESULTS}/fidelity/limits"


rule method_limits:
    input:
        expand(f"{LIMITS}/{{study}}.nc", study=LIMIT_STUDIES),
        expand(f"{LIMITS}/method_limits_{{study}}.png", study=LIMIT_STUDIES),


rule limits_study:
    input:
        lambda wc: [f"{RESULTS}/campaign/dataset.nc"] if wc.study == "kriging_coverage" else [],
    output:
        nc=f"{LIMITS}/{{study}}.nc",
        png=report(f"{LIMITS}/method_limits_{{study}}.png", category="Fidelity and method limits",
                   caption="../report/method_limits.rst"),
    wildcard_constraints:
        study="|".join(LIMIT_STUDIES),
    params:
        config=sections(*SURROGATE),
        sizes=[20, 40, 60, 100],
    threads: 1
    resources:
        mem_mb=scaled(700),
        runtime=45,
    log:
        log_file("fidelity/limits_{study}"),
    benchmark:
        benchmark_file("fidelity/limits_{study}")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/limits_study.py"
