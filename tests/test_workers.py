"""The worker pool runs each task on one BLAS/OpenMP thread, whatever the thread count of the job that
starts it (Snakemake sets OMP_NUM_THREADS etc. to the rule's ``threads``)."""
import pytest
from threadpoolctl import threadpool_limits

from ringdamper.workers import THREAD_VARIABLES, worker_pool


def _threads_in_worker(_):
    """The thread counts of the BLAS and OpenMP libraries the Kriging fits use, seen from a worker."""
    import numpy  # noqa: F401  (load the libraries whose pools are inspected)
    import openturns  # noqa: F401
    import scipy.linalg  # noqa: F401
    from threadpoolctl import threadpool_info
    return sorted({(i["internal_api"], i["num_threads"]) for i in threadpool_info()})


@pytest.mark.parametrize("start_method", ["fork", "spawn"])
def test_workers_are_single_threaded_in_a_two_thread_job(monkeypatch, start_method):
    for name in THREAD_VARIABLES:
        monkeypatch.setenv(name, "2")
    import openturns  # noqa: F401  (a forked worker inherits the parent's loaded libraries and limits)
    import scipy.linalg  # noqa: F401
    with threadpool_limits(2):
        with worker_pool(2, start_method) as pool:
            seen = list(pool.map(_threads_in_worker, range(2)))
    for threads in seen:
        assert {api for api, _ in threads} >= {"openblas", "openmp"}
        assert all(n == 1 for _, n in threads), threads
