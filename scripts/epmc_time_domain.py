"""Rule script: the time-domain check of the rising EPMC frequencies of the Jenkins chain family
(ringdamper.nonlinear.jenkins_chains, ringdamper.studies.epmc_time_domain; docs/nonlinear_core.md,
"Time-domain check of the EPMC"):

1. the frequency rise ``max ω/ω_stuck − 1`` of every chain of the family (H = 1 on the family's grid
   and settings) -> ``rise``;
2. on the two chains with the largest rise and on seed 149 (the simplest rising chain: two masses,
   one element), HBM backbones at H = 1, 3, 7, 15 on a 16-point grid and time-domain shooting at
   every third amplitude -> ``comparison`` and the ``figure``;
3. the return errors of seed 179's backbones at H = 3 (a branch no other H finds) and at H = 15
   -> ``return_179``;
4. the linear viscous analogue of seed 149 (its element replaced by a damper c, 0 … 1000)
   -> ``viscous_149``;
5. Δt convergence of the shooting at two points (seed 43 at the top of the grid, seed 149 at its
   first strongly slipping amplitude) -> ``steps``;
6. the folding chain ``issue_chain`` (ζ up to 0.41): HBM at H = 1 and 15 and shooting from H = 15
   at every amplitude -> ``issue_chain``.
"""
import time

import numpy as np
import pandas as pd

from ringdamper.logs import to_file
from ringdamper.nonlinear.epmc import epmc
from ringdamper.nonlinear.jenkins_chains import ISSUE_GRID, OPTIONS, SEEDS, chain_grid, issue_chain, jenkins_chain
from ringdamper.nonlinear.structure import Structure
from ringdamper.plots.epmc_time_domain import plot_comparison
from ringdamper.studies.epmc_time_domain import (
    compare,
    damper_poles,
    frequency_rise,
    return_check,
    step_convergence,
    stuck_frequency,
)

SIMPLEST = 149
SPURIOUS = 179


def dense_grid(st, c):
    """The family grid with 16 points: every third one is a point of the 6-point family grid."""
    return chain_grid(st, c, n=16)


sm = snakemake  # noqa: F821 (injected by Snakemake)
log = to_file(sm.log[0])
t0 = time.process_time()
rises = []
for seed in SEEDS:
    st, c = jenkins_chain(seed)
    bb = epmc(st, c, chain_grid(st, c), **OPTIONS)
    rises.append(dict(seed=seed, masses=st.harmonics[0].M.shape[0], elements=c.npairs,
                      omega_stuck=stuck_frequency(st, c),
                      rise=frequency_rise(bb, stuck_frequency(st, c))))
rise = pd.DataFrame(rises)
rise.to_csv(sm.output.rise, index=False, float_format="%.6g")
log.info("scan: %.1f s CPU, %d of %d chains rise", time.process_time() - t0,
         int((rise.rise > 1e-6).sum()), len(rise))

worst = list(rise.sort_values("rise", ascending=False).seed.iloc[:2])
tables = {}
for seed in worst + [SIMPLEST]:
    t0 = time.process_time()
    st, c = jenkins_chain(seed)
    tables[seed] = compare(lambda H, s=seed: jenkins_chain(s, H=H)[0], c, dense_grid(st, c))
    log.info("seed %d: %.1f s CPU", seed, time.process_time() - t0)
pd.concat([t.assign(seed=s) for s, t in tables.items()]).to_csv(
    sm.output.comparison, index=False, float_format="%.8g")
plot_comparison(tables, sm.output.figure)

st, c = jenkins_chain(SPURIOUS)
pd.concat([return_check(lambda H: jenkins_chain(SPURIOUS, H=H)[0], c, chain_grid(st, c), H)
           for H in (3, 15)]).to_csv(sm.output.return_179, index=False, float_format="%.6g")
damper_poles(jenkins_chain(SIMPLEST)[0], 0, np.r_[0.0, np.geomspace(0.1, 1e3, 9)]).to_csv(
    sm.output.viscous_149, index=False, float_format="%.6g")

steps = []
for seed, i in ((43, 15), (SIMPLEST, 6)):
    st, c = jenkins_chain(seed, H=15)
    bb = epmc(st, c, dense_grid(st, c), H=15, nt=1024, tol=1e-10)
    steps.append(step_convergence(st, c, bb, i).assign(seed=seed))
pd.concat(steps).to_csv(sm.output.steps, index=False, float_format="%.10g")

st, c = issue_chain()
hd = st.harmonics[1]


def issue_at(H):
    """The folding chain at ``H`` harmonics."""
    return Structure.real(hd.M, hd.K, hd.B, hd.response, hd.force, H=H)


compare(issue_at, c, ISSUE_GRID, harmonics=(1, 15), shoot_every=1).merge(
    return_check(issue_at, c, ISSUE_GRID, 1).rename(columns={"return_hbm": "return_h1"})
    [["H", "alpha", "return_h1"]], on=["H", "alpha"], how="left").to_csv(
    sm.output.issue_chain, index=False, float_format="%.8g")
