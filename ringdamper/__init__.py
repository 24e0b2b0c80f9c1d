"""ringdamper: geometric design of friction ring dampers in blisks.

Implements Sun, Denimal, Yuan, Salles, *Geometric design of friction ring dampers in blisks using
nonlinear modal analysis and Kriging surrogate model*, Struct. Multidisc. Optim. 2022. The packages
follow the paper's method chain: geometry → fem → modal → static → reduction → nonlinear → campaign
→ plots; studies and bench hold the studies and benchmarks (docs/design.md §1 and
docs/paper_map.md). :mod:`ringdamper.status` holds the status codes of the nonlinear results
(dnnm.nc, the forced responses, the campaign dataset), which every layer reads. Every stage is
importable without Snakemake.
"""

__version__ = "0.1.0"
