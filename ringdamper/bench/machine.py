"""The machine a benchmark ran on, and its speed in the operation the dNNM spends most of its time on.

Benchmark seconds compare only on one machine: the same code took about 2.7 times longer a core on an
AMD EPYC with AVX2 only (Zen 1) than on one with AVX-512
(docs/investigations/2026-12-01-campaign-timings.md). Every
``make bench`` file therefore records the CPU, the BLAS library with the kernel it loaded (OpenBLAS
chooses one for the CPU at start-up, ``threadpoolctl``'s ``architecture``) and the CPU time of a
*reference LU*: LAPACK's ``dgetrf`` of a dense real matrix of order :data:`REFERENCE_ORDER`, the size of
the default ring's condensed Jacobian at H = 3, on one thread. A dNNM's CPU time divided by it, the
time in reference LUs, is the figure meant to compare between machines (dense factorisations are a
third to a half of a dNNM; docs/design.md §8).
"""
from __future__ import annotations

import multiprocessing as mp
import os
import platform
import time

import numpy as np
import scipy.linalg as sla

#: order of the reference LU: the default ring's condensed Jacobian at H = 3 (70 pairs, 3 directions,
#: 2H + 1 = 7 real slots each, and 6 explicit modes)
REFERENCE_ORDER = 1476
#: factorisations timed; the median is reported
REPEATS = 7


def cpu_model() -> str:
    """The CPU's model name (``/proc/cpuinfo`` on Linux, else :func:`platform.processor`)."""
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def blas_libraries() -> list[dict]:
    """Each BLAS the process loaded (sorted): its implementation, version and the kernel it chose
    (None where the library does not say, e.g. MKL)."""
    from threadpoolctl import threadpool_info

    keys = ("internal_api", "version", "architecture")
    found = {tuple(info.get(k) for k in keys) for info in threadpool_info() if info.get("user_api") == "blas"}
    return [dict(zip(keys, values)) for values in sorted(found, key=lambda values: tuple(map(str, values)))]


def reference_lu_seconds(order: int = REFERENCE_ORDER, repeats: int = REPEATS, seed: int = 0) -> float:
    """Median CPU seconds of one ``dgetrf`` of a random ``order × order`` matrix (uniform entries,
    Fortran order, copied before each timing so that only the factorisation is timed), BLAS on one
    thread."""
    from threadpoolctl import threadpool_limits

    a = np.asfortranarray(np.random.default_rng(seed).random((order, order)))
    times = []
    with threadpool_limits(limits=1):
        for _ in range(repeats):
            work = a.copy(order="F")
            start = time.process_time()
            sla.lu_factor(work, overwrite_a=True, check_finite=False)
            times.append(time.process_time() - start)
    return float(np.median(times))


def describe() -> dict:
    """The machine record of a benchmark file (module docstring)."""
    return {"cpus": mp.cpu_count(), "cpu_model": cpu_model(), "python": platform.python_version(),
            "load_average_1min": os.getloadavg()[0],
            "blas_threads": os.environ.get("OPENBLAS_NUM_THREADS"), "blas": blas_libraries(),
            "reference_lu_order": REFERENCE_ORDER, "reference_lu_s": reference_lu_seconds()}
