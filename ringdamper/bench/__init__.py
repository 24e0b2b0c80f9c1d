"""Benchmarks (``make bench``, i.e. ``python -m ringdamper.bench``): wall time, peak memory and sizes of
the stages (:mod:`.__main__`), the nonlinear core on a synthetic system of the real size
(:mod:`.dynamics`) and the static contact solver on a synthetic two-block case (:mod:`.static_synthetic`)."""
