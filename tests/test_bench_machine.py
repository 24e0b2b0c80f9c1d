"""The machine record of the benchmark files (ringdamper.bench.machine)."""
import numpy as np

from ringdamper.bench.machine import REFERENCE_ORDER, blas_libraries, cpu_model, describe


def test_machine_record_names_cpu_blas_kernel_and_reference_lu():
    record = describe()
    assert record["cpus"] >= 1 and record["cpu_model"] == cpu_model() != ""
    assert record["blas"] == blas_libraries() and record["blas"], "no BLAS found by threadpoolctl"
    assert all(lib["internal_api"] for lib in record["blas"])
    assert all(lib["architecture"] for lib in record["blas"] if lib["internal_api"] == "openblas"), \
        "OpenBLAS without the kernel it chose"
    assert record["reference_lu_order"] == REFERENCE_ORDER
    assert np.isfinite(record["reference_lu_s"]) and record["reference_lu_s"] > 0

