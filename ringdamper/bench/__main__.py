"""``python -m ringdamper.bench``: run the benchmarks of :mod:`ringdamper.bench.run`."""
from ringdamper.bench.run import main

main()
