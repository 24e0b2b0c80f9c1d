"""Worker processes for work that is parallel across tasks, each task single-threaded.

Snakemake gives a job of ``threads: n`` the environment OMP_NUM_THREADS = OPENBLAS_NUM_THREADS = … = n.
A job that spends its n threads on n worker processes must then keep every worker's BLAS and OpenMP to
one thread: n processes × n threads on n cores busy-wait on one another (OpenBLAS and libgomp spin
before they sleep). Measured on the adaptive design's first round with the estimated nugget, 2 cores:
146 s wall and 290 s CPU with two 2-thread workers, 15 s and 27 s with two 1-thread workers. The
limits are set in the worker twice over: in its environment, for the libraries it has not loaded yet
(spawned workers), and through threadpoolctl for those it has (forked workers inherit the parent's).
"""
from __future__ import annotations

import multiprocessing
import os
from concurrent.futures import ProcessPoolExecutor

from threadpoolctl import threadpool_limits

#: The thread-count variables Snakemake sets for a job (and OpenBLAS' own), set to 1 in every worker.
THREAD_VARIABLES = ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "GOTO_NUM_THREADS", "MKL_NUM_THREADS",
                    "VECLIB_MAXIMUM_THREADS", "NUMEXPR_NUM_THREADS")


def single_threaded() -> None:
    """Limit the calling process to one BLAS/OpenMP thread, for the libraries loaded now and later."""
    os.environ.update(dict.fromkeys(THREAD_VARIABLES, "1"))
    threadpool_limits(1)


def worker_pool(workers: int, start_method: str | None = None) -> ProcessPoolExecutor:
    """``workers`` processes, each single-threaded (:func:`single_threaded` is their initializer);
    ``start_method`` "fork", "spawn" or None (the platform's default)."""
    context = multiprocessing.get_context(start_method)
    return ProcessPoolExecutor(workers, mp_context=context, initializer=single_threaded)
