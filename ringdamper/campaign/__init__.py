"""Campaign-level stages over all geometries (paper §3.2–3.4): from the design of experiments and
the dataset of every dnnm.nc to the surrogates, their exploration, the Sobol indices, the optimum's
check and the comparison with the paper (docs/analytics.md, docs/surrogate.md, docs/optimum_frf.md)."""
