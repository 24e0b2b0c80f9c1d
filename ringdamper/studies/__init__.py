"""Studies that fix the model's choices, run by ``make studies`` into ``results/studies/``: the hub
thickness calibration (:mod:`.hub_calibration`), the contact calibration (:mod:`.contact_calibration`),
the contact state of the reference rings (:mod:`.contact_state`), the mesh convergence
(:mod:`.mesh_convergence`), the reduction convergence (:mod:`.reduction_convergence`), the last
grid amplitude (:mod:`.last_point`) and the EPMC's time-domain check (:mod:`.epmc_time_domain`);
with ``make fidelity``, the fidelity dials (:mod:`.fidelity`) and the methods' limits
(:mod:`.method_limits`). ``make studies`` and ``make fidelity`` then publish the committed tables and
figures to ``docs/`` (:mod:`ringdamper.publish`). A study returns its data (rows, datasets); the rule scripts draw its
figures from them."""
