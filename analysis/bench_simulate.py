"""Benchmark of the forward simulation: real-time factors and the command's wall time.

Run:  python analysis/bench_simulate.py [--cycles 10]

1. The built-in hexapod with the default springs (the optimal linear femur springs, all native:
   one ``mujoco.rollout`` call per run), both controllers: simulated seconds per wall-clock second
   of the stepping, µs per step. Target ≥ 50× real time.
2. The same gait with preloaded dead-zone springs on the femurs (native too: the preload's step is
   a clamped actuator) — the kind of springs ``hexaleg design`` recommends. Target ≥ 50×.
3. Damped dead-zone springs on the femurs (the damping acts only while engaged: a non-native
   term, the run steps in Python): its real-time factor and its cost against the native run.
4. ``hexaleg simulate`` on the default robot, end to end in a fresh process (imports, robot,
   gait, optimal springs, two runs of 4 cycles, the JSON and the page). Target ≤ 30 s.
Best of three runs for 1–3; timings depend on the machine and its load, so the benchmark prints
its own CPU share: on the 2-core machine, two other busy processes halve every factor (time
slicing), while one leaves them unchanged.
"""

from __future__ import annotations

import argparse
import dataclasses
import subprocess
import sys
import tempfile
import time

import numpy as np

from hexaleg.commands.simulate.study import load_study
from hexaleg.robot.springs import DeadZoneSpring, PreloadedSpring, SpringSet
from hexaleg.scenario.scenario import Scenario
from hexaleg.simulation.run import simulate

CPU_SHARE: list[float] = []
"""This thread's CPU time over the wall time of each timed call: below ~0.9 the process waited
for a core (other jobs on the machine), and the real-time factors are understated by as much."""


def best_of(fn, n: int = 3):
    runs = []
    for _ in range(n):
        wall, cpu = time.perf_counter(), time.thread_time()
        runs.append(fn())
        CPU_SHARE.append((time.thread_time() - cpu) / (time.perf_counter() - wall))
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
    study = load_study(Scenario.load("hexaleg"))
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
    damped = SpringSet({j: DeadZoneSpring(stiffness=0.5, theta_k=0.05, damping=0.002, neutral=c)
                        for j, c in centre.items()})

    def run(springs: SpringSet):
        return best_of(lambda: simulate(robot, motion, p.motor, springs, settings,
                                        contact=p.contact, prepared=p))

    report("feedforward, preloaded (rollout)", run(preloaded))
    python = report("feedforward, damped dead zone (Python)", run(damped))
    print(f"  Python stepping costs {factors['feedforward'] / python:.1f}× the native rollout")
    share = min(CPU_SHARE)
    print(f"  CPU time / wall time of the timed runs: ≥ {share:.2f}"
          + ("" if share > 0.9 else "  (the machine was busy: the factors above are low by up "
                                    f"to {1 / share:.1f}×; rerun on a quiet machine)"))
    with tempfile.TemporaryDirectory() as out:
        start = time.perf_counter()
        subprocess.run([sys.executable, "-m", "hexaleg.cli", "simulate", "--out", out],
                       check=True, capture_output=True)
        wall = time.perf_counter() - start
    print(f"hexaleg simulate (default robot, fresh process): {wall:.1f} s wall (target ≤ 30 s)")


if __name__ == "__main__":
    main()
