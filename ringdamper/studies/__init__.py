"""Studies that fix the model's choices, run by ``make studies`` into ``results/studies/``: the hub
thickness calibration (:mod:`.hub_calibration`), the contact calibration (:mod:`.contact_calibration`),
the mesh convergence (:mod:`.mesh_convergence`) and the reduction convergence
(:mod:`.reduction_convergence`)."""
