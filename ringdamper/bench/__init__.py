"""Benchmarks of the stages and of the solvers on synthetic systems of the real size (``make bench``,
i.e. ``python -m ringdamper.bench``): wall time, peak memory and sizes."""
