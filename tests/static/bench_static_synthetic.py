"""Timing of the static contact solver on a synthetic ≈15k-DoF two-block case (not a test).

Run from the worktree root:  python tests/static/bench_static_synthetic.py [--linear]
Prints the DoF and pair counts, the assembly time and, per method, the solve time, iterations,
residuals and the number of closed pairs. Timings are reported, never asserted.
"""
import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path[:0] = [str(Path(__file__).resolve().parents[2]), str(Path(__file__).resolve().parent)]
from static_systems import two_blocks  # noqa: E402

from ringdamper.contact.static import solve_static_contact  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--linear", action="store_true", help="Q1 bricks (default: Q2, 27 nodes)")
    args = parser.parse_args()
    nx, nz = (12, 14) if args.linear else (6, 7)
    t = time.perf_counter()
    system = two_blocks(nx=nx, nz=nz, height=1.0, quadratic=not args.linear,
                        gap=lambda x, y: 0.3 * ((x - 0.5) ** 2 + (y - 0.5) ** 2))
    print(f"{'Q1' if args.linear else 'Q2'} two blocks: {system.K.shape[0]} DoFs, "
          f"{system.g0.size} pairs, assembly {time.perf_counter() - t:.2f} s")
    for method in ("penalty", "lagrange"):
        t = time.perf_counter()
        r = solve_static_contact(system.K, system.f, system.G, system.g0, 1e4, 1e3, method=method)
        print(f"{method:9s} {time.perf_counter() - t:6.2f} s  status {r.status} ({r.reason}), "
              f"{r.iterations} iterations, residual {r.residual:.1e}, complementarity "
              f"{r.complementarity:.1e}, {np.count_nonzero(r.in_contact)} closed pairs, "
              f"ΣN = {r.N0.sum():.12f}")


if __name__ == "__main__":
    main()
