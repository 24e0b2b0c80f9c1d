"""Static contact under centrifugal load (paper §2.4, §3.1.2; docs/static_contact.md): the
frictionless unilateral contact solver, the static stage of one geometry, and synthetic problems with
analytic or converged solutions."""
