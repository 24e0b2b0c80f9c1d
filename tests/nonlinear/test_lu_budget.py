"""LU budgets (ringdamper.nonlinear.solvers.budget): each factorisation is charged, the one past the
limit stops the work before it factorises, budgets nest."""
import numpy as np
import pytest

from ringdamper.nonlinear.solvers.budget import LUBudgetExceeded, lu_budget
from ringdamper.nonlinear.solvers.newton import factorize

J = np.array([[4.0, 1.0], [1.0, 3.0]])


def test_the_factorisation_past_the_limit_raises_and_the_ones_within_count():
    with lu_budget(2) as budget:
        factorize(J, None, 2)
        factorize(J, None, 2)
        assert budget.used == 2
        with pytest.raises(LUBudgetExceeded, match="LU budget of 2 factorisations exceeded"):
            factorize(J, None, 2)


def test_nested_budgets_are_each_charged_and_no_budget_has_no_limit():
    with lu_budget(None) as outer:
        with lu_budget(1) as inner:
            factorize(J, None, 2)
        factorize(J, None, 2)
    assert (outer.used, inner.used) == (2, 1)
    factorize(J, None, 2)                               # outside every budget: not charged
    assert outer.used == 2
