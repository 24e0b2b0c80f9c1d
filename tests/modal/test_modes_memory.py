"""Modal solves: memory flat in the number of calls (nothing of one nodal diameter's solve, its
projected matrices, LU factors and Krylov basis, outlives it, even with the garbage collector off),
and the same modes to the bit from call to call."""
import gc
import tracemalloc

import numpy as np
import pytest

from ringdamper.fem.model import build_model, stuck_contact_stiffness
from ringdamper.geometry.sector import build_sector
from ringdamper.modal.analysis import cyclic_modes


@pytest.fixture(scope="module")
def stuck_model(small_config):
    model = build_model(build_sector(small_config, (0.0, 0.0, 0.0)), small_config)
    return model, model.K + stuck_contact_stiffness(model, small_config["contact"])


def test_cyclic_modes_leave_no_reference_cycle_and_flat_memory(stuck_model):
    """Six complex NDs in a row with gc disabled: over the last five calls the traced memory grows
    by less than a tenth of one projected stiffness matrix (a few kB of interpreter caches; with
    eigsh's ``sigma=`` and ``M=`` it grew by two such matrices per ND), and a collection finds
    nothing to free."""
    model, K = stuck_model
    gc.collect()
    gc.disable()
    tracemalloc.start()
    try:
        after = []
        for nd in range(1, 7):
            modes = cyclic_modes(model, K, model.M, nd, 4)
            del modes
            after.append(tracemalloc.get_traced_memory()[0])
        unreachable = gc.collect()
    finally:
        tracemalloc.stop()
        gc.enable()
    n = model.n_dofs
    one_matrix = 16 * K.nnz + 8 * n  # complex values + indices of a projected matrix, roughly
    assert after[-1] - after[0] < 0.1 * one_matrix, (np.diff(after), one_matrix)
    assert unreachable == 0


def test_cyclic_modes_are_identical_from_call_to_call(stuck_model):
    """The seeded start vector makes a repeated solve bitwise identical (ARPACK's random one differed
    by ~1e-9 from run to run)."""
    model, K = stuck_model
    first, second = (cyclic_modes(model, K, model.M, 2, 4) for _ in range(2))
    assert np.array_equal(first.frequency, second.frequency)
    assert np.array_equal(first.shapes, second.shapes)
