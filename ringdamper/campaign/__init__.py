"""Campaign-level stages over all geometries (paper §3.2–3.4): the design of experiments
(:mod:`.sampling`)."""
