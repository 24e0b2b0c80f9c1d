# The studies that fixed the model's choices (ringdamper.studies): `make studies` -> results/studies/.
# Settings: the `studies` section of the configuration. Resources as for the campaign's rules
# (common.smk: mem_mb about twice the peak RSS, runtime ten times the wall time, at least 5 min), from
# the benchmarks of one `make studies` run on the shared 2-core machine (results/benchmarks/studies/;
# contact_calibration: its slowest stage, coarse, 26 min on 2 threads, and its largest peak, 0.97 GB in
# harmonics_B; the figure and table rules read small files, as the campaign's figure rules: <= 0.3 GB).
from ringdamper.studies.contact_calibration.dataset import FIGURE_STAGES, STAGES as CALIBRATION_STAGES

STUDIES = f"{RESULTS}/studies"
STUDY_REDUCED = f"{STUDIES}/default_reduced.nc"
EPMC_CHECK = f"{STUDIES}/epmc_time_domain"
EPMC_CHECK_TABLES = ("rise", "comparison", "return_179", "viscous_149", "steps", "issue_chain")
STUDY = DNNM + ("studies",)  # the configuration sections of the studies' outputs (common.smk)


# Harmonics the studies' default-ring reduced model needs: the contact calibration's and the last-point
# study's largest H (at least the campaign's).
STUDY_HARMONICS = max([config["dnnm"]["n_harmonics"],
                       *config.get("studies", {}).get("contact_calibration", {}).get("harmonics", []),
                       config.get("studies", {}).get("last_point", {}).get("n_harmonics", 0)])


rule studies:
    input:
        f"{STUDIES}/hub_calibration.yaml",
        f"{STUDIES}/mesh_convergence.csv",
        f"{STUDIES}/reduction_convergence.csv",
        expand(f"{STUDIES}/contact_calibration/{{stage}}.csv",
               stage=CALIBRATION_STAGES),
        f"{STUDIES}/contact_calibration/calibration_default_backbone.png",
        f"{STUDIES}/contact_calibration/tables.md",
        f"{STUDIES}/contact_state/contact_state_designs.csv",
        f"{STUDIES}/contact_state/contact_state_backbone.csv",
        f"{STUDIES}/last_point/last_point_separation.png",
        expand(f"{EPMC_CHECK}/{{table}}.csv", table=EPMC_CHECK_TABLES),
        f"{EPMC_CHECK}/epmc_time_domain.png",


rule study_reduced:
    output:
        STUDY_REDUCED,
    params:
        config=sections(*REDUCED, "dnnm", "studies"),
        harmonics=STUDY_HARMONICS,
    threads: 1
    resources:
        mem_mb=scaled(1000),
        runtime=5,
    log:
        log_file("studies/study_reduced"),
    benchmark:
        benchmark_file("studies/study_reduced")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/study_reduced.py"


rule study_hub_calibration:
    output:
        f"{STUDIES}/hub_calibration.yaml",
    params:
        config=sections(*STUDY),
    threads: 1
    resources:
        mem_mb=scaled(700),
        runtime=5,
    log:
        log_file("studies/hub_calibration"),
    benchmark:
        benchmark_file("studies/hub_calibration")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/study_hub_calibration.py"


rule study_mesh_convergence:
    output:
        f"{STUDIES}/mesh_convergence.csv",
    params:
        config=sections(*STUDY),
    threads: 1
    resources:
        mem_mb=scaled(3300),
        runtime=14,
    log:
        log_file("studies/mesh_convergence"),
    benchmark:
        benchmark_file("studies/mesh_convergence")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/study_mesh_convergence.py"


rule study_reduction_convergence:
    output:
        csv=f"{STUDIES}/reduction_convergence.csv",
        table=f"{STUDIES}/reduction_convergence.md",
    params:
        config=sections(*STUDY),
    threads: 1
    resources:
        mem_mb=scaled(1000),
        runtime=22,
    log:
        log_file("studies/reduction_convergence"),
    benchmark:
        benchmark_file("studies/reduction_convergence")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/study_reduction_convergence.py"


rule study_contact_calibration:
    input:
        reduced=STUDY_REDUCED,
        resonance=f"{RESULTS}/modal/resonance.yaml",
    output:
        table=f"{STUDIES}/contact_calibration/{{stage}}.csv",
        curves=f"{STUDIES}/contact_calibration/{{stage}}.npz",
    wildcard_constraints:
        stage="|".join(CALIBRATION_STAGES),
    params:
        config=sections(*STUDY),
    threads: 2
    resources:
        mem_mb=scaled(2000),
        runtime=262,
    log:
        log_file("studies/contact_calibration_{stage}"),
    benchmark:
        benchmark_file("studies/contact_calibration_{stage}")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/study_contact_calibration.py"


rule study_contact_figures:
    input:
        expand(f"{STUDIES}/contact_calibration/{{stage}}.npz", stage=FIGURE_STAGES),
    output:
        backbone=report(f"{STUDIES}/contact_calibration/calibration_default_backbone.png",
                        category="Studies"),
        examples=report(f"{STUDIES}/contact_calibration/calibration_coarse_examples.png",
                        category="Studies"),
    params:
        config=sections(*STUDY),
    threads: 1
    resources:
        mem_mb=scaled(600),
        runtime=5,
    log:
        log_file("studies/contact_calibration_figures"),
    benchmark:
        benchmark_file("studies/contact_calibration_figures")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/study_contact_figures.py"


rule study_contact_tables:
    input:
        expand(f"{STUDIES}/contact_calibration/{{stage}}.csv",
               stage=CALIBRATION_STAGES),
    output:
        f"{STUDIES}/contact_calibration/tables.md",
    threads: 1
    resources:
        mem_mb=scaled(600),
        runtime=5,
    log:
        log_file("studies/contact_calibration_tables"),
    benchmark:
        benchmark_file("studies/contact_calibration_tables")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/study_contact_tables.py"


rule study_contact_state:
    output:
        rings=f"{STUDIES}/contact_state/contact_state_rings.csv",
        designs=f"{STUDIES}/contact_state/contact_state_designs.csv",
        search=report(f"{STUDIES}/contact_state/contact_state_search.png", category="Studies"),
        maps_configured=f"{STUDIES}/contact_state/contact_state_maps_configured.png",
        maps_best=f"{STUDIES}/contact_state/contact_state_maps_best.png",
        closure=f"{STUDIES}/contact_state/contact_state_free_closure.png",
        closure_table=f"{STUDIES}/contact_state/contact_state_free_closure.csv",
    params:
        config=sections(*STUDY),
    threads: 1
    resources:
        mem_mb=scaled(800),
        runtime=90,
    log:
        log_file("studies/contact_state"),
    benchmark:
        benchmark_file("studies/contact_state")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/study_contact_state.py"


rule study_contact_state_backbone:
    input:
        reduced=f"{RESULTS}/geometry/{DEFAULT_GID}/reduced.nc",
        resonance=f"{RESULTS}/modal/resonance.yaml",
    output:
        table=f"{STUDIES}/contact_state/contact_state_backbone.csv",
        figure=report(f"{STUDIES}/contact_state/contact_state_backbone.png", category="Studies"),
    params:
        config=sections(*STUDY),
    threads: 1
    resources:
        mem_mb=scaled(700),
        runtime=6,
    log:
        log_file("studies/contact_state_backbone"),
    benchmark:
        benchmark_file("studies/contact_state_backbone")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/study_contact_state_backbone.py"


rule study_last_point:
    input:
        reduced=STUDY_REDUCED,
        static=f"{RESULTS}/geometry/{DEFAULT_GID}/static.nc",
        resonance=f"{RESULTS}/modal/resonance.yaml",
    output:
        campaign=f"{STUDIES}/last_point/campaign.nc",
        fine=f"{STUDIES}/last_point/fine.nc",
        figure=report(f"{STUDIES}/last_point/last_point_separation.png", category="Studies",
                      caption="../report/last_point_separation.rst"),
    params:
        config=sections(*STUDY),
    threads: 1
    resources:
        mem_mb=scaled(1000),
        runtime=16,
    log:
        log_file("studies/last_point"),
    benchmark:
        benchmark_file("studies/last_point")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/study_last_point.py"


# The EPMC against time-domain shooting on the Jenkins chain family (docs/nonlinear_core.md,
# "Time-domain check of the EPMC"): small analytic systems, no configuration. Measured on the shared
# 2-core machine at load 16: 400 s of CPU (40 min wall), peak RSS 167 MB.
rule epmc_time_domain:
    output:
        **{table: f"{EPMC_CHECK}/{table}.csv" for table in EPMC_CHECK_TABLES},
        figure=report(f"{EPMC_CHECK}/epmc_time_domain.png", category="Studies",
                      caption="../report/epmc_time_domain.rst"),
    threads: 1
    resources:
        mem_mb=scaled(400),
        runtime=70,
    log:
        log_file("studies/epmc_time_domain"),
    benchmark:
        benchmark_file("studies/epmc_time_domain")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/epmc_time_domain.py"
