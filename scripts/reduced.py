"""Rule script: kappa (+ mesh.vtu, static.nc) -> results/geometry/{gid}/reduced.nc (DESIGN §3.3, §4).

The model is rebuilt from kappa (mesh.vtu is the dependency that pins it); static.nc gives the contact
state used only to log the linearised stuck frequencies (pairs with N0 > 0 stuck, the others open).
"""
import os
import resource
import time

import numpy as np

from ringdamper.io import read_netcdf, write_netcdf
from ringdamper.reduction import (modal_basis, modal_stuck_frequencies, pair_stiffness, reduce_sector,
                                  reduced_dataset)
from ringdamper.fem.model import build_model
from ringdamper.geometry.sector import build_sector

sm = snakemake  # noqa: F821 (injected by Snakemake)
t0 = time.perf_counter()
cfg = sm.config
settings = cfg["reduction"]
n_fi = settings["n_fixed_interface_modes"]
n_if = settings["n_interface_modes"]
n_h = settings["n_harmonics"]

model = build_model(build_sector(cfg, sm.params.kappa), cfg)
t_model = time.perf_counter() - t0
rs = reduce_sector(model, cfg["operation"]["engine_order"], n_harmonics=n_h, n_fi=n_fi, n_if=n_if)
bases = [modal_basis(rh, rs.B, rs.response_index) for rh in rs.harmonics]
ds = reduced_dataset(rs, sm.params.kappa, bases,
                     attrs={"stiffness": "linear elastic at rest (no prestress)",
                            "wall_time_s": time.perf_counter() - t0})
write_netcdf(ds, sm.output[0])

static = read_netcdf(sm.input.static)
if static.sizes["pair"] != len(model.pairs):
    raise ValueError(f"static.nc has {static.sizes['pair']} pairs, the model {len(model.pairs)}")
kn, kt = pair_stiffness(model.pairs.area, static["N0"].values, cfg["contact"])
with open(sm.log[0], "w") as log:
    log.write(f"kappa={sm.params.kappa} n_fi={n_fi} n_if={n_if} harmonics=0..{n_h}\n")
    log.write(f"dofs {rs.dof_counts}\n")
    log.write(f"time: model {t_model:.2f} s, {', '.join(f'{k} {v:.2f} s' for k, v in rs.timings.items())}, "
              f"total {time.perf_counter() - t0:.2f} s\n")
    log.write(f"pairs stuck (N0 > 0): {int(np.sum(kn > 0))} of {len(kn)}\n")
    for rh, b in zip(rs.harmonics, bases):
        f = modal_stuck_frequencies(b.omega2, b.contact, kn, kt, 5)
        log.write(f"h={rh.harmonic} ND{rh.nd}: stuck frequencies (Hz) {np.round(f, 3).tolist()}\n")
    log.write(f"file {os.path.getsize(sm.output[0]) / 1e6:.2f} MB, peak memory "
              f"{resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024:.0f} MB\n")
