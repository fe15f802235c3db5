"""Benchmark of the forward simulation: real-time factors and the command's wall time.

Run:  python analysis/bench_simulate.py [--cycles 10]

1. The built-in hexapod with the default springs (the optimal linear femur springs, all native:
   one ``mujoco.rollout`` call per run), both controllers: simulated seconds per wall-clock second
   of the stepping, µs per step. Target ≥ 50× real time.
2. The same gait with preloaded dead-zone springs (a non-native term: the run steps in Python):
   its real-time factor and its cost against the native run.
3. ``hexaleg simulate`` on the default robot, end to end in a fresh process (imports, robot,
   gait, optimal springs, two runs of 4 cycles, the JSON and the page). Target ≤ 30 s.
Best of three runs for 1 and 2; timings depend on the machine and its load.
"""

from __future__ import annotations

import argparse
import dataclasses
import subprocess
import sys
import tempfile
import time

import numpy as np

from hexaleg.robot.springs import PreloadedSpring, SpringSet
from hexaleg.studies.simulate.run import simulate
from hexaleg.studies.simulate.study import load_study


def best_of(fn, n: int = 3):
    runs = [fn() for _ in range(n)]
    return min(runs, key=lambda s: s.with_springs.wall)


def report(label: str, s) -> float:
    run = s.with_springs
    steps = run.trajectory.n
    print(f"  {label:<38} dt {run.sim.timestep * 1e3:g} ms: {run.realtime_factor:5.1f}× real time, "
          f"{run.wall / steps * 1e6:5.1f} µs/step ({steps} steps, {run.wall:.3f} s)")
    return run.realtime_factor


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--cycles", type=int, default=10)
    args = parser.parse_args()
    study = load_study("hexaleg")
    settings = dataclasses.replace(study.settings, cycles=args.cycles, evaluate=2,
                                   force_samples=0)
    print(f"hexaleg default gait, {args.cycles} cycles:")
    factors = {}
    for controller in ("feedforward", "position"):
        s = best_of(lambda c=controller: dataclasses.replace(
            study, settings=dataclasses.replace(settings, controller=c)).run())
        factors[controller] = report(f"{controller}, native springs (rollout)", s)
    p = study.prepared
    robot, motion = p.robot, p.motion
    centre = {j: float(np.mean(motion.q[:, robot.model.joints[robot.model.getJointId(j)].idx_q]))
              for j in robot.joints("femur")}
    preloaded = SpringSet({j: PreloadedSpring(stiffness=0.5, preload=0.02, theta_k=0.05,
                                              neutral=c) for j, c in centre.items()})
    s = best_of(lambda: simulate(robot, motion, p.motor, preloaded, settings, contact=p.contact,
                                 prepared=p))
    python = report("feedforward, preloaded (Python steps)", s)
    print(f"  Python stepping costs {factors['feedforward'] / python:.1f}× the native rollout")
    with tempfile.TemporaryDirectory() as out:
        start = time.perf_counter()
        subprocess.run([sys.executable, "-m", "hexaleg.cli", "simulate", "--out", out],
                       check=True, capture_output=True)
        wall = time.perf_counter() - start
    print(f"hexaleg simulate (default robot, fresh process): {wall:.1f} s wall (target ≤ 30 s)")


if __name__ == "__main__":
    main()
