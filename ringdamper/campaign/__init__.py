"""Campaign-level stages over all geometries (paper §3.2–3.4): the design of experiments
(:mod:`.sampling`); every dnnm.nc on one geometry × amplitude dataset (:mod:`.dataset`); ordinary
Kriging per output and amplitude (:mod:`.kriging`) and its validation (:mod:`.validation`); the
design space on the surrogates: sweeps, the 50³ grid, the optimum (:mod:`.exploration`); Sobol
indices (:mod:`.sensitivity`, per response level :mod:`.sobol_levels`); the optimum against its
computed backbone (:mod:`.optimum_check`) and the forced responses against the E-EBM
(:mod:`.forced_check`); summaries and the comparison with the paper for the report
(:mod:`.summary`, :mod:`.paper`, :mod:`.report_tables`). See docs/analytics.md, docs/surrogate.md
and docs/optimum_frf.md."""
