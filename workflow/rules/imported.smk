# The import report of a user's own blisk sector (geometry.source: imported; docs/imported.md):
# `snakemake --configfile my.yaml <results>/imported/blisk_nd.csv`, or `make check-import CONFIG=my.yaml`.
# The mesh file's SHA-256 is a param, so editing the file reruns the job, and the report records it.
from ringdamper.imported.report import file_sha256

IMPORTED = ("material", "imported", "operation", "modal.n_modes")


rule imported_report:
    input:
        mesh=config["imported"]["mesh"],
    output:
        nd=f"{RESULTS}/imported/blisk_nd.csv",
        report=f"{RESULTS}/imported/report.yaml",
    params:
        config=sections(*IMPORTED),
        mesh_sha256=file_sha256(config["imported"]["mesh"]),
    threads: 1
    resources:
        mem_mb=3000,
        runtime=10,
    log:
        log_file("imported_report"),
    benchmark:
        benchmark_file("imported_report")
    conda:
        "../../envs/ringdamper.yaml"
    script:
        "../../scripts/imported_report.py"


rule check_import:
    input:
        rules.imported_report.output.nd,
