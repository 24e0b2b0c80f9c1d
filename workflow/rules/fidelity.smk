# The fidelity study (ringdamper.studies.fidelity, docs/fidelity.md): `make fidelity` -> results/fidelity/.
# Not part of `all`. Settings: the `fidelity` section of the configuration.
from ringdamper.studies.fidelity.dials import dial_cases

FIDELITY = f"{RESULTS}/fidelity"
FIDELITY_CASES = dial_cases(config) if "fidelity" in config else []
MESH_BACKBONE_FACTORS = config.get("fidelity", {}).get("mesh_backbone", {}).get("factors", [])


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
    threads: 1
    resources:
        mem_mb=scaled(1600),
        runtime=40,
    log:
        f"{RESULTS}/logs/fidelity/{{ring}}_{{dial}}_{{value}}.log",
    benchmark:
        f"{RESULTS}/benchmarks/fidelity/{{ring}}_{{dial}}_{{value}}.tsv"
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
    threads: 1
    resources:
        mem_mb=twice_the_peak(mesh_level_peak_mb),
        runtime=25,
    log:
        f"{RESULTS}/logs/fidelity/mesh_{{factor}}_{{order}}.log",
    benchmark:
        f"{RESULTS}/benchmarks/fidelity/mesh_{{factor}}_{{order}}.tsv"
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
    threads: 1
    resources:
        mem_mb=twice_the_peak(mesh_backbone_peak_mb),
        runtime=60,
    log:
        f"{RESULTS}/logs/fidelity/mesh_backbone_{{factor}}.log",
    benchmark:
        f"{RESULTS}/benchmarks/fidelity/mesh_backbone_{{factor}}.tsv"
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
        factors=MESH_BACKBONE_FACTORS,
    log:
        f"{RESULTS}/logs/fidelity/mesh_backbone.log",
    benchmark:
        f"{RESULTS}/benchmarks/fidelity/mesh_backbone.tsv"
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
        cases=[list(key) for key in FIDELITY_CASES],
    log:
        f"{RESULTS}/logs/fidelity/dials.log",
    benchmark:
        f"{RESULTS}/benchmarks/fidelity/dials.tsv"
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
    log:
        f"{RESULTS}/logs/fidelity/mesh.log",
    benchmark:
        f"{RESULTS}/benchmarks/fidelity/mesh.tsv"
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
        default_gid=DEFAULT_GID,
    threads: 1
    resources:
        mem_mb=scaled(1000),
        runtime=40,
    log:
        f"{RESULTS}/logs/fidelity/surrogate.log",
    benchmark:
        f"{RESULTS}/benchmarks/fidelity/surrogate.tsv"
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
    log:
        f"{RESULTS}/logs/fidelity/forced.log",
    benchmark:
        f"{RESULTS}/benchmarks/fidelity/forced.tsv"
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
        dials=report(f"{FIDELITY}/fidelity_dials.png", category="Fidelity"),
        mesh=report(f"{FIDELITY}/fidelity_mesh.png", category="Fidelity"),
        pareto=report(f"{FIDELITY}/fidelity_pareto.png", category="Fidelity"),
    params:
        n_geometries=len(geometry_ids()),
        n_validation=int((SAMPLES.split == "validation").sum()),
        n_cores=2,
    log:
        f"{RESULTS}/logs/fidelity/summary.log",
    benchmark:
        f"{RESULTS}/benchmarks/fidelity/summary.tsv"
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/fidelity_summary.py"
