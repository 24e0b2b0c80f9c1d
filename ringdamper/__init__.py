"""ringdamper: geometric design of friction ring dampers in blisks.

Implements Sun, Denimal, Yuan, Salles, *Geometric design of friction ring dampers in blisks using
nonlinear modal analysis and Kriging surrogate model*, Struct. Multidisc. Optim. 2022. The packages
follow the paper's method chain (docs/design.md §1, docs/paper_map.md); every stage is importable
without Snakemake.
"""

__version__ = "0.1.0"
