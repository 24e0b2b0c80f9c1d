"""Rule script: the default ring's linearised stuck frequency of the target mode, computed once.

The dNNM of every geometry is normalised by it (omega0 = 2.195 omega / omega_stuck,default), and
its target mode is the harmonic-1 stuck mode nearest the modal stage's resonance.
"""
import yaml

from ringdamper.nonlinear.stage import contacts_from_static, structure_from_reduced, target_stuck_frequency
from ringdamper.io import read_netcdf, write_yaml

sm = snakemake  # noqa: F821 (injected by Snakemake)
target_hz = yaml.safe_load(open(sm.input.resonance))["frequency_hz"]
structure = structure_from_reduced(read_netcdf(sm.input.reduced), 1)
contacts = contacts_from_static(read_netcdf(sm.input.static), sm.config["contact"],
                                sm.config["dnnm"]["friction_law"])
omega = target_stuck_frequency(structure, contacts, target_hz)
write_yaml({"target_frequency_hz": float(target_hz), "omega_stuck_default_rad_s": omega}, sm.output[0])
open(sm.log[0], "w").write(f"omega_stuck_default = {omega:.6f} rad/s\n")
