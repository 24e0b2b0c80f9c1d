"""Time-domain check of the rising EPMC frequencies of the chain family of
``tests/nonlinear/test_continuation_family.py`` (docs/nonlinear_core.md, "Time-domain check of the
EPMC"); run from the repository root:

    OMP_NUM_THREADS=1 python -m tools.epmc_time_domain [--out docs/epmc_time_domain]

1. the frequency rise ``max ω/ω_stuck − 1`` of every chain (seeds 0..199, H = 1 on the family's
   grid and settings) -> ``rise.csv``;
2. on the two chains with the largest rise and on seed 149 (the simplest rising chain: two masses,
   one element), HBM backbones at H = 1, 3, 7, 15 on a 16-point grid and time-domain shooting at
   every third amplitude -> ``comparison.csv`` and ``docs/figures/epmc_time_domain.png``;
3. the return errors of seed 179's backbones at H = 3 (a branch no other H finds) and at H = 15
   -> ``return_179.csv``;
4. the linear viscous analogue of seed 149 (its element replaced by a damper c, 0 … 1000)
   -> ``viscous_149.csv``;
5. Δt convergence of the shooting at two points (seed 43 at the top of the grid, seed 149 at its
   first strongly slipping amplitude) -> ``steps.csv``;
6. the folding chain of the family test (``issue_chain``, ζ up to 0.41): HBM at H = 1 and 15 and
   shooting from H = 15 at every amplitude -> ``issue_chain.csv``.
"""
import argparse
import logging
import time
from pathlib import Path

import numpy as np
import pandas as pd

from ringdamper.nonlinear.epmc import epmc
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
from tests.nonlinear.systems import jenkins_chain
from tests.nonlinear.test_continuation_family import ISSUE_GRID, OPTIONS, SEEDS, chain_grid, issue_chain

SIMPLEST = 149
SPURIOUS = 179


def dense_grid(st, c):
    """The family grid with 16 points: every third one is a point of the 6-point family grid."""
    return chain_grid(st, c, n=16)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default="docs/epmc_time_domain")
    parser.add_argument("--figure", default="docs/figures/epmc_time_domain.png")
    args = parser.parse_args()
    logging.basicConfig(level=logging.INFO, format="%(asctime)s %(name)s %(message)s")
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    t0 = time.process_time()
    rises = []
    for seed in SEEDS:
        st, c = jenkins_chain(seed)
        bb = epmc(st, c, chain_grid(st, c), **OPTIONS)
        rises.append(dict(seed=seed, masses=st.harmonics[0].M.shape[0], elements=c.npairs,
                          omega_stuck=stuck_frequency(st, c),
                          rise=frequency_rise(bb, stuck_frequency(st, c))))
    rise = pd.DataFrame(rises)
    rise.to_csv(out / "rise.csv", index=False, float_format="%.6g")
    logging.info("scan: %.1f s CPU, %d of %d chains rise", time.process_time() - t0,
                 int((rise.rise > 1e-6).sum()), len(rise))
    worst = list(rise.sort_values("rise", ascending=False).seed.iloc[:2])
    tables = {}
    for seed in worst + [SIMPLEST]:
        t0 = time.process_time()
        st, c = jenkins_chain(seed)
        tables[seed] = compare(lambda H, s=seed: jenkins_chain(s, H=H)[0], c, dense_grid(st, c))
        logging.info("seed %d: %.1f s CPU", seed, time.process_time() - t0)
    pd.concat([t.assign(seed=s) for s, t in tables.items()]).to_csv(
        out / "comparison.csv", index=False, float_format="%.8g")
    plot_comparison(tables, args.figure)
    st, c = jenkins_chain(SPURIOUS)
    pd.concat([return_check(lambda H: jenkins_chain(SPURIOUS, H=H)[0], c, chain_grid(st, c), H)
               for H in (3, 15)]).to_csv(out / f"return_{SPURIOUS}.csv", index=False,
                                         float_format="%.6g")
    damper_poles(jenkins_chain(SIMPLEST)[0], 0, np.r_[0.0, np.geomspace(0.1, 1e3, 9)]).to_csv(
        out / f"viscous_{SIMPLEST}.csv", index=False, float_format="%.6g")
    steps = []
    for seed, i in ((43, 15), (SIMPLEST, 6)):
        st, c = jenkins_chain(seed, H=15)
        bb = epmc(st, c, dense_grid(st, c), H=15, nt=1024, tol=1e-10)
        steps.append(step_convergence(st, c, bb, i).assign(seed=seed))
    pd.concat(steps).to_csv(out / "steps.csv", index=False, float_format="%.10g")
    st, c = issue_chain()
    hd = st.harmonics[1]

    def issue_at(H):
        return Structure.real(hd.M, hd.K, hd.B, hd.response, hd.force, H=H)

    compare(issue_at, c, ISSUE_GRID, harmonics=(1, 15), shoot_every=1).merge(
        return_check(issue_at, c, ISSUE_GRID, 1).rename(columns={"return_hbm": "return_h1"})
        [["H", "alpha", "return_h1"]], on=["H", "alpha"], how="left").to_csv(
        out / "issue_chain.csv", index=False, float_format="%.8g")


if __name__ == "__main__":
    main()
