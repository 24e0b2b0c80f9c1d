"""Studies that fix the model's choices (``make studies`` into ``results/studies/``, ``make fidelity``),
each returning its data (rows, datasets) for the rule scripts and ``plots`` to write and draw
(docs/model.md, docs/calibration.md, docs/fidelity.md, docs/method_limits.md); their committed
tables and figures reach ``docs/`` through :mod:`ringdamper.publish`. The seeded Jenkins chains that
studies and tests share are :mod:`ringdamper.studies.jenkins_chains`."""
