"""Benchmark of the spring design program: the whole robot's optimal springs in one convex solve.

Run:  python analysis/bench_design.py [--samples 1000] [--repeat 5]

For the default tripod gait and three class groups (coxa, femur, tibia; joule objective, one
shared design per class) it times, at a fixed geometry, the fast path (condensed active set,
:func:`hexaleg.design.program.solve_design`) and the cvxpy reference
(:func:`hexaleg.design.program_reference.solve_design_reference`) on the same program, on a floor
where no inequality binds (μ = 0.6) and where the friction cones bind (μ = 0.3, the paper's
Table 3 static friction), and prints their ratio and agreement; then the whole
``optimal_springs`` call with the geometry searched. Targets (issue "Springs as decision
variables"): ≤ 50 ms when nothing binds, ≤ 2 s otherwise. Last, the wall time of the two
commands a user runs, each a fresh process (imports included): ``hexaleg design`` with its maps
and robust design (target ≤ 30 s, issue "The design answer") and ``hexaleg report`` (≤ 8 s).
"""

from __future__ import annotations

import argparse
import time

import numpy as np

import hexaleg
from hexaleg.design.codesign import design_problem, optimal_springs
from hexaleg.design.program import solve_design
from hexaleg.design.program_reference import solve_design_reference

CLASSES = ["coxa", "femur", "tibia"]
GEOMETRY = {"linear": {}, "dead_zone": {"theta_minus": -0.1, "theta_plus": 0.05}}


def _best(fn, repeat: int) -> tuple[float, object]:
    best, out = np.inf, None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=1000)
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    robot = hexaleg.load_robot()
    motion = hexaleg.tripod_gait(robot, hexaleg.GaitParams(samples=args.samples))
    print(f"default tripod gait, {motion.n_samples} samples per cycle, 3 class groups, joule")
    for mu in (0.6, 0.3):
        prepared = hexaleg.prepare(robot, motion, contact=hexaleg.ContactParams(mu=mu))
        prepared.baseline()  # the gains and the baseline: once per gait, as in a study
        for fam, g in GEOMETRY.items():
            problem = design_problem(prepared, CLASSES, fam, {c: g for c in CLASSES})
            t_fast, fast = _best(lambda p=problem: solve_design(p), args.repeat)
            t_ref, ref = _best(lambda p=problem: solve_design_reference(p), 1)
            rel = abs(fast.value - ref.value) / ref.value
            print(f"μ = {mu}  {fam:<9}  fast {1e3 * t_fast:8.1f} ms ({fast.rounds} solves, "
                  f"{fast.explicit.size:4d} explicit samples)   cvxpy {1e3 * t_ref:8.1f} ms   "
                  f"ratio {t_ref / t_fast:6.1f} x   |Δvalue|/value {rel:.1e}   "
                  f"max |Δx| {np.abs(fast.x - ref.x).max():.1e}")
    prepared = hexaleg.prepare(robot, motion)
    for fam in ("linear", "dead_zone", "preloaded", "one_sided"):
        t, res = _best(lambda f=fam: optimal_springs(prepared, CLASSES, f), 1)
        print(f"optimal_springs {fam:<9} geometry searched: {t:6.2f} s, "
              f"{res.solver['geometry_evaluations']:4d} convex solves, joule saving "
              f"{100 * res.saving:+.2f} %, electrical "
              f"{100 * res.analysis.savings['total']['electrical']:+.2f} %")


def _wall(args: list[str]) -> float:
    """Wall time of ``hexaleg ARGS`` in a fresh process, s."""
    import subprocess
    import sys
    import tempfile

    with tempfile.TemporaryDirectory() as out:
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-m", "hexaleg.cli", *args, "--out", out], check=True,
                       capture_output=True)
        return time.perf_counter() - t0


def commands() -> None:
    """The wall time of ``hexaleg design`` and ``hexaleg report`` on the default robot."""
    for name, target in (("design", 30.0), ("report", 8.0)):
        t = _wall([name])
        print(f"hexaleg {name:<7} {t:6.1f} s wall (target ≤ {target:g} s)")


if __name__ == "__main__":
    main()
    commands()
