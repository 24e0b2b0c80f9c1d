# The fidelity study (ringdamper.studies.fidelity, docs/fidelity.md): `make fidelity` -> results/fidelity/.
# Not part of `all`. Settings: the `fidelity` section of the configuration.
from ringdamper.studies.fidelity.dials import dial_cases

FIDELITY = f"{RESULTS}/fidelity"
FIDELITY_CASES = dial_cases(config) if "fidelity" in config else []
MESH_BACKBONE_FACTORS = config.get("fidelity", {}).get("mesh_backbone", {}).get("factors", [])
FIDELITY_SUMMARY = DNNM + ("frf", "sensitivity", "exploration", "fidelity")  # sections (common.smk)


# The fidelity study's resources, from the committed measurements of the last `make fidelity` (docs/fidelity/*.csv; the
# rules' convention of common.smk, with CPU instead of wall times: that run's walls were 3-10x its CPU
# on the loaded machine): a dial case peaks at 792 MB and 223 s of chain CPU (H = 5 on the optimum);
# a mesh level at the peak RSS of MESH_LEVEL_PEAK_MB (the 3x quadratic one 7.0 GB, 149 s); the
# surrogate study's 15 designs fit in 224 s of CPU.
MESH_LEVEL_PEAK_MB = {(1, 1): 199, (2, 1): 258, (3, 1): 667, (1, 2): 322, (2, 2): 1713, (3, 2): 6967}


# Peak RSS (MB) of the whole chain on the default ring at H = 3 with 60 grid pairs (fidelity.mesh_backbone)
# per mesh refinement factor (measured: the reduction of the refined sector dominates; chain CPU 12 s and
# 108 s); beyond the measured factors, that of the largest scaled with the element count, factor³.
MESH_BACKBONE_PEAK_MB = {1: 509, 2: 2921}
MESH_BACKBONE_PEAKS = {factor: MESH_BACKBONE_PEAK_MB.get(factor, MESH_BACKBONE_PEAK_MB[2] * (factor / 2) ** 3)
                       for factor in MESH_BACKBONE_FACTORS}


rule fidelity:
    input:
        f"{FIDELITY}/dials.csv",
        f"{FIDELITY}/mesh.csv",
        f"{FIDELITY}/mesh_backbone.csv",
        f"{FIDELITY}/surrogate.csv",
        f"{FIDELITY}/forced.csv",
        f"{FIDELITY}/summary.yaml",
        rules.method_limits.input,


rule fidelity_case:
    input:
        resonance=f"{RESULTS}/modal/resonance.yaml",
    output:
        f"{FIDELITY}/cases/{{ring}}/{{dial}}/{{value}}.nc",
    params:
        config=sections(*DNNM, "fidelity.rings", "fidelity.dials"),
    threads: 1
    resources:
        mem_mb=scaled(1600),
        runtime=40,
    log:
        log_file("fidelity/{ring}_{dial}_{value}"),
    benchmark:
        benchmark_file("fidelity/{ring}_{dial}_{value}")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/fidelity_case.py"


rule fidelity_mesh_level:
    output:
        f"{FIDELITY}/mesh/{{factor}}_{{order}}.yaml",
    wildcard_constraints:
        factor=r"\d+",
        order=r"\d+",
    params:
        config=sections(*MODAL, "fidelity.mesh_families"),
    threads: 1
    resources:
        # twice the measured peak of the level (of the 3x quadratic one if not measured), per attempt
        mem_mb=lambda wildcards, attempt: 2 * attempt * MESH_LEVEL_PEAK_MB.get(
            (int(wildcards.factor), int(wildcards.order)), MESH_LEVEL_PEAK_MB[3, 2]),
        runtime=25,
    log:
        log_file("fidelity/mesh_{factor}_{order}"),
    benchmark:
        benchmark_file("fidelity/mesh_{factor}_{order}")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/fidelity_mesh_level.py"


rule fidelity_mesh_backbone_case:
    input:
        resonance=f"{RESULTS}/modal/resonance.yaml",
    output:
        f"{FIDELITY}/mesh_backbone/{{factor}}.nc",
    wildcard_constraints:
        factor=r"\d+",
    params:
        config=sections(*DNNM, "fidelity.mesh_backbone"),
    threads: 1
    resources:
        mem_mb=lambda wildcards, attempt: int(2 * attempt * MESH_BACKBONE_PEAKS[int(wildcards.factor)]),
        runtime=60,
    log:
        log_file("fidelity/mesh_backbone_{factor}"),
    benchmark:
        benchmark_file("fidelity/mesh_backbone_{factor}")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/fidelity_mesh_backbone_case.py"


rule fidelity_mesh_backbone:
    input:
        [f"{FIDELITY}/mesh_backbone/{factor}.nc" for factor in MESH_BACKBONE_FACTORS],
    output:
        f"{FIDELITY}/mesh_backbone.csv",
    params:
        config=sections(*FIDELITY_SUMMARY),
        factors=MESH_BACKBONE_FACTORS,
    threads: 1
    resources:
        mem_mb=scaled(400),
        runtime=5,
    log:
        log_file("fidelity/mesh_backbone"),
    benchmark:
        benchmark_file("fidelity/mesh_backbone")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/fidelity_mesh_backbone.py"


rule fidelity_dials:
    input:
        [f"{FIDELITY}/cases/{ring}/{dial}/{value}.nc" for ring, dial, value in FIDELITY_CASES],
    output:
        f"{FIDELITY}/dials.csv",
    params:
        config=sections(*FIDELITY_SUMMARY),
        cases=[list(key) for key in FIDELITY_CASES],
    threads: 1
    resources:
        mem_mb=scaled(400),
        runtime=5,
    log:
        log_file("fidelity/dials"),
    benchmark:
        benchmark_file("fidelity/dials")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/fidelity_dials.py"


rule fidelity_mesh:
    input:
        [f"{FIDELITY}/mesh/{factor}_{order}.yaml" for factor, order in config.get("fidelity", {}).get("mesh_levels", [])],
    output:
        levels=f"{FIDELITY}/mesh.csv",
        limits=f"{FIDELITY}/mesh_limits.csv",
    params:
        config=sections(*FIDELITY_SUMMARY),
    threads: 1
    resources:
        mem_mb=scaled(400),
        runtime=5,
    log:
        log_file("fidelity/mesh"),
    benchmark:
        benchmark_file("fidelity/mesh")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/fidelity_mesh.py"


rule fidelity_surrogate:
    input:
        f"{RESULTS}/campaign/dataset.nc",
    output:
        f"{FIDELITY}/surrogate.csv",
    params:
        config=sections(*EXPLORATION, "frf", "sensitivity", "fidelity"),
        default_gid=DEFAULT_GID,
    threads: 1
    resources:
        mem_mb=scaled(1000),
        runtime=40,
    log:
        log_file("fidelity/surrogate"),
    benchmark:
        benchmark_file("fidelity/surrogate")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/fidelity_surrogate.py"


rule fidelity_forced:
    input:
        table3=f"{RESULTS}/frf/table3.csv",
        dnnm_default=f"{RESULTS}/geometry/{DEFAULT_GID}/dnnm.nc",
        dnnm_optimum=f"{RESULTS}/geometry/{OPTIMUM_GID}/dnnm.nc",
        frf_default=frf_curves(DEFAULT_GID),
        frf_optimum=frf_curves(OPTIMUM_GID),
    output:
        f"{FIDELITY}/forced.csv",
    threads: 1
    resources:
        mem_mb=scaled(400),
        runtime=5,
    log:
        log_file("fidelity/forced"),
    benchmark:
        benchmark_file("fidelity/forced")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/fidelity_forced.py"


rule fidelity_summary:
    input:
        dials=f"{FIDELITY}/dials.csv",
        mesh=f"{FIDELITY}/mesh.csv",
        surrogate=f"{FIDELITY}/surrogate.csv",
    output:
        summary=f"{FIDELITY}/summary.yaml",
        dials=report(f"{FIDELITY}/fidelity_dials.png", category="Fidelity and method limits",
                     caption="../report/fidelity_dials.rst"),
        mesh=report(f"{FIDELITY}/fidelity_mesh.png", category="Fidelity and method limits",
                    caption="../report/fidelity_mesh.rst"),
        pareto=report(f"{FIDELITY}/fidelity_pareto.png", category="Fidelity and method limits",
                      caption="../report/fidelity_pareto.rst"),
    params:
        config=sections(*FIDELITY_SUMMARY),
        n_geometries=len(geometry_ids()),
        n_validation=int((SAMPLES.split == "validation").sum()),
        n_cores=lambda wildcards: workflow.cores,  # the cores of this run (--cores; profiles/default: 2)
    threads: 1
    resources:
        mem_mb=scaled(400),
        runtime=5,
    log:
        log_file("fidelity/summary"),
    benchmark:
        benchmark_file("fidelity/summary")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/fidelity_summary.py"
