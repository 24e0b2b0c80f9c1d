# The studies that fixed the model's choices (ringdamper.studies): `make studies` -> results/studies/.
# Settings: the `studies` section of the configuration. Resources as for the campaign's rules
# (common.smk: mem_mb about twice the peak RSS, runtime ten times the wall time, at least 5 min), from
# the benchmarks of one `make studies` run on the shared 2-core machine (results/benchmarks/studies/;
# contact_calibration: its slowest stage, coarse, 26 min on 2 threads, and its largest peak, 0.97 GB in
# harmonics_B; the figure and table rules read small files, as the campaign's figure rules: <= 0.3 GB).
STUDIES = f"{RESULTS}/studies"
STUDY_REDUCED = f"{STUDIES}/default_reduced.nc"


rule studies:
    input:
        f"{STUDIES}/hub_calibration.yaml",
        f"{STUDIES}/mesh_convergence.csv",
        f"{STUDIES}/reduction_convergence.csv",
        expand(f"{STUDIES}/contact_calibration/{{stage}}.csv",
               stage=("coarse", "refine", "harmonics_A", "harmonics_B")),
        f"{STUDIES}/contact_calibration/calibration_default_backbone.png",
        f"{STUDIES}/contact_calibration/tables.md",
        f"{STUDIES}/contact_state/contact_state_designs.csv",
        f"{STUDIES}/contact_state/contact_state_backbone.csv",
        f"{STUDIES}/last_point/last_point_separation.png",


rule study_reduced:
    output:
        STUDY_REDUCED,
    params:
        harmonics=study_harmonics(config),
    threads: 1
    resources:
        mem_mb=scaled(1000),
        runtime=5,
    log:
        f"{RESULTS}/logs/studies/study_reduced.log",
    benchmark:
        f"{RESULTS}/benchmarks/studies/study_reduced.tsv"
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/study_reduced.py"


rule hub_calibration:
    output:
        f"{STUDIES}/hub_calibration.yaml",
    threads: 1
    resources:
        mem_mb=scaled(700),
        runtime=5,
    log:
        f"{RESULTS}/logs/studies/hub_calibration.log",
    benchmark:
        f"{RESULTS}/benchmarks/studies/hub_calibration.tsv"
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/study_hub_calibration.py"


rule mesh_convergence:
    output:
        f"{STUDIES}/mesh_convergence.csv",
    threads: 1
    resources:
        mem_mb=scaled(3300),
        runtime=14,
    log:
        f"{RESULTS}/logs/studies/mesh_convergence.log",
    benchmark:
        f"{RESULTS}/benchmarks/studies/mesh_convergence.tsv"
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/study_mesh_convergence.py"


rule reduction_convergence:
    output:
        csv=f"{STUDIES}/reduction_convergence.csv",
        table=f"{STUDIES}/reduction_convergence.md",
    threads: 1
    resources:
        mem_mb=scaled(1000),
        runtime=22,
    log:
        f"{RESULTS}/logs/studies/reduction_convergence.log",
    benchmark:
        f"{RESULTS}/benchmarks/studies/reduction_convergence.tsv"
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/study_reduction_convergence.py"


rule contact_calibration:
    input:
        reduced=STUDY_REDUCED,
        resonance=f"{RESULTS}/modal/resonance.yaml",
    output:
        table=f"{STUDIES}/contact_calibration/{{stage}}.csv",
        curves=f"{STUDIES}/contact_calibration/{{stage}}.npz",
    wildcard_constraints:
        stage="coarse|refine|harmonics_A|harmonics_B",
    threads: 2
    resources:
        mem_mb=scaled(2000),
        runtime=262,
    log:
        f"{RESULTS}/logs/studies/contact_calibration_{{stage}}.log",
    benchmark:
        f"{RESULTS}/benchmarks/studies/contact_calibration_{{stage}}.tsv"
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/study_contact_calibration.py"


rule contact_calibration_figures:
    input:
        expand(f"{STUDIES}/contact_calibration/{{stage}}.npz", stage=("coarse", "refine", "harmonics_A")),
    output:
        backbone=report(f"{STUDIES}/contact_calibration/calibration_default_backbone.png",
                        category="Studies"),
        examples=report(f"{STUDIES}/contact_calibration/calibration_coarse_examples.png",
                        category="Studies"),
    threads: 1
    resources:
        mem_mb=scaled(600),
        runtime=5,
    log:
        f"{RESULTS}/logs/studies/contact_calibration_figures.log",
    benchmark:
        f"{RESULTS}/benchmarks/studies/contact_calibration_figures.tsv"
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/study_contact_figures.py"


rule contact_calibration_tables:
    input:
        expand(f"{STUDIES}/contact_calibration/{{stage}}.csv",
               stage=("coarse", "refine", "harmonics_A", "harmonics_B")),
    output:
        f"{STUDIES}/contact_calibration/tables.md",
    threads: 1
    resources:
        mem_mb=scaled(600),
        runtime=5,
    log:
        f"{RESULTS}/logs/studies/contact_calibration_tables.log",
    benchmark:
        f"{RESULTS}/benchmarks/studies/contact_calibration_tables.tsv"
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/study_contact_tables.py"


rule contact_state:
    output:
        rings=f"{STUDIES}/contact_state/contact_state_rings.csv",
        designs=f"{STUDIES}/contact_state/contact_state_designs.csv",
        search=report(f"{STUDIES}/contact_state/contact_state_search.png", category="Studies"),
        maps_configured=f"{STUDIES}/contact_state/contact_state_maps_configured.png",
        maps_best=f"{STUDIES}/contact_state/contact_state_maps_best.png",
        closure=f"{STUDIES}/contact_state/contact_state_free_closure.png",
        closure_table=f"{STUDIES}/contact_state/contact_state_free_closure.csv",
    threads: 1
    resources:
        mem_mb=scaled(800),
        runtime=90,
    log:
        f"{RESULTS}/logs/studies/contact_state.log",
    benchmark:
        f"{RESULTS}/benchmarks/studies/contact_state.tsv"
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/study_contact_state.py"


rule contact_state_backbone:
    input:
        reduced=f"{RESULTS}/geometry/{DEFAULT_GID}/reduced.nc",
        resonance=f"{RESULTS}/modal/resonance.yaml",
    output:
        table=f"{STUDIES}/contact_state/contact_state_backbone.csv",
        figure=report(f"{STUDIES}/contact_state/contact_state_backbone.png", category="Studies"),
    threads: 1
    resources:
        mem_mb=scaled(700),
        runtime=6,
    log:
        f"{RESULTS}/logs/studies/contact_state_backbone.log",
    benchmark:
        f"{RESULTS}/benchmarks/studies/contact_state_backbone.tsv"
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/study_contact_state_backbone.py"


rule last_point:
    input:
        reduced=STUDY_REDUCED,
        static=f"{RESULTS}/geometry/{DEFAULT_GID}/static.nc",
        resonance=f"{RESULTS}/modal/resonance.yaml",
    output:
        campaign=f"{STUDIES}/last_point/campaign.nc",
        fine=f"{STUDIES}/last_point/fine.nc",
        figure=report(f"{STUDIES}/last_point/last_point_separation.png", category="Studies"),
    threads: 1
    resources:
        mem_mb=scaled(1000),
        runtime=16,
    log:
        f"{RESULTS}/logs/studies/last_point.log",
    benchmark:
        f"{RESULTS}/benchmarks/studies/last_point.tsv"
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/study_last_point.py"
