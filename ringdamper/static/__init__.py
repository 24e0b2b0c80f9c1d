"""Static contact under centrifugal load (paper §2.4, §3.1.2): the frictionless unilateral contact
solver (:mod:`.solver`), the static stage of one geometry (:mod:`.stage`), the pairs' closure in a
static state (:mod:`.closure`) and synthetic problems with analytic or converged solutions
(:mod:`.synthetic`, oracles of the tests and the benchmark)."""
