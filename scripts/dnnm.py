"""Rule script: reduced.nc + static.nc -> dnnm.nc (EPMC backbone + E-EBM on the common alpha grid).

The target mode is the harmonic-1 stuck mode nearest the resonance of the modal stage; omega0 is
normalised by the default ring's linearised stuck frequency (both from stuck_default.yaml). A failure writes dnnm.nc with
status 99 and the reason, so the campaign goes on (DESIGN §5).
"""
import traceback

import numpy as np
import yaml

from ringdamper.nonlinear.stage import failed_dnnm, run_dnnm
from ringdamper.io import read_netcdf, write_netcdf

sm = snakemake  # noqa: F821 (injected by Snakemake)
cfg = sm.config
with open(sm.log[0], "w") as log:
    try:
        static = read_netcdf(sm.input.static)
        if static.attrs["status"] != 0:
            raise RuntimeError(f"static solve failed: {static.attrs['reason']}")
        norm = yaml.safe_load(open(sm.input.normalisation))
        ds = run_dnnm(read_netcdf(sm.input.reduced), static, cfg, norm["target_frequency_hz"],
                      norm["omega_stuck_default_rad_s"])
        counts = np.bincount(ds.status.values.astype(int), minlength=5)
        log.write(f"kappa={sm.params.kappa} status counts {counts.tolist()} "
                  f"wall {ds.attrs['wall_time_s']:.1f} s\n")
    except Exception as err:  # a failed geometry must not stop the campaign
        log.write(traceback.format_exc())
        ds = failed_dnnm(cfg, sm.params.kappa, f"{type(err).__name__}: {err}")
    write_netcdf(ds, sm.output[0])
