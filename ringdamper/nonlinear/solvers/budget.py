"""A hard budget of LU factorisations for a block of work (docs/nonlinear_core.md §4.5).

Inside ``with lu_budget(n):`` every LU factorisation of the Newton solvers
(:class:`ringdamper.nonlinear.solvers.newton.Factorization`, also those a continuation or a lagged
solver makes) is charged to the budget; the one past ``n`` raises :class:`LUBudgetExceeded` before it
factorises, which ends the work where it stands. Budgets nest: a factorisation is charged to each open
one. Outside any budget a factorisation costs one empty-list check.
"""
from __future__ import annotations

from collections import Counter
from contextlib import contextmanager
from dataclasses import dataclass, field

_open: list = []                        # the budgets open, innermost last


class LUBudgetExceeded(RuntimeError):
    """More LU factorisations than an open :func:`lu_budget` allows."""


@dataclass
class LUBudget:
    """``limit`` LU factorisations allowed (None: no limit), ``used`` the ones charged so far and
    ``kinds`` their count by kind (``"full"``: the whole Newton system; ``"nonlinear_rows"``)."""

    limit: int | None
    used: int = 0
    kinds: Counter = field(default_factory=Counter)


@contextmanager
def lu_budget(limit: int | None):
    """Charge the LU factorisations of the block to a new :class:`LUBudget` of ``limit`` (yielded)."""
    budget = LUBudget(limit)
    _open.append(budget)
    try:
        yield budget
    finally:
        _open.remove(budget)


def charge_lu(kind: str = "full") -> None:
    """One LU factorisation of ``kind`` about to be made: charged to every open budget; raises
    :class:`LUBudgetExceeded` if that takes one past its limit."""
    for budget in _open:
        budget.used += 1
        budget.kinds[kind] += 1
        if budget.limit is not None and budget.used > budget.limit:
            raise LUBudgetExceeded(f"LU budget of {budget.limit} factorisations exceeded")
