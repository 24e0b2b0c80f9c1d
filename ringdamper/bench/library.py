"""Benchmark of the library on NLvib's published example systems, as ``docs/examples/`` computes them:
the first nonlinear mode of example 05 (2 DoF, tanh friction, EPMC at H = 21, 1024 samples, 41
amplitudes) and the forced response of example 07 (3 DoF, five elements of three kinds, H = 7, 1024
samples, 0.5 → 2 rad/s). CPU seconds of this process, points solved (grid points and continuation
points) and CPU per point: the figures to set against NLvib's on the same systems and point counts.
:func:`run` returns the figures; it asserts nothing.
"""
from __future__ import annotations

import importlib.util
import time
from pathlib import Path

EXAMPLES = Path(__file__).resolve().parents[2] / "docs" / "examples"


def load_example(name: str):
    """The module ``docs/examples/<name>.py`` (the examples are scripts, not a package)."""
    spec = importlib.util.spec_from_file_location(name, EXAMPLES / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _timed(compute) -> tuple:
    start = time.process_time()
    result = compute()
    return result, time.process_time() - start


def run(config: dict | None = None) -> dict:
    """CPU s, points and ms per point of the two NLvib systems (``config`` unused: the systems are
    the published ones)."""
    tanh = load_example("tanh_friction_nm")
    (backbone, _), cpu = _timed(tanh.mode)
    points = int(backbone.branch.shape[0])
    out = {"nlvib05_epmc": {"H": tanh.H, "nt": tanh.NT, "grid_points": int(backbone.alpha.size),
                            "continuation_points": points, "cpu_s": cpu,
                            "cpu_ms_per_point": 1e3 * cpu / max(points, 1)}}
    chain = load_example("chain_multiple_nonlinearities")
    (frf, _), cpu = _timed(chain.curve)
    out["nlvib07_frf"] = {"H": chain.H, "nt": chain.NT, "points": int(frf.omega.size), "cpu_s": cpu,
                          "cpu_ms_per_point": 1e3 * cpu / max(frf.omega.size, 1)}
    return out
