"""Benchmark of the core analysis: time per stiffness choice, fast path vs per-sample cvxpy.

Run:  python analysis/bench_core.py [--samples 1000] [--reference-samples 100]

Prints, for the default tripod gait, the one-off ``prepare`` time, the time of one
``Prepared.evaluate(springs)`` (fast exact path), the time per sample of the cvxpy reference
(measured on ``--reference-samples`` evenly spaced samples and scaled to the cycle), their ratio,
and the largest force difference between the two paths on the samples solved by both.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

import hexaleg
from hexaleg.dynamics.prepare import prepare
from hexaleg.dynamics.reference import solve_reference


def _best(fn, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=1000)
    parser.add_argument("--reference-samples", type=int, default=100)
    parser.add_argument("--repeat", type=int, default=20)
    args = parser.parse_args()

    robot = hexaleg.load_robot()
    motion = hexaleg.tripod_gait(robot, hexaleg.GaitParams(samples=args.samples))
    t_prep = _best(lambda: prepare(robot, motion), 3)
    prepared = prepare(robot, motion)
    prepared.evaluate(None)  # caches the gains and the no-spring baseline
    ks = np.linspace(0.2, 3.0, args.repeat)
    designs = [{leg.joint_names[1]: hexaleg.DeadZoneSpring(stiffness=k, theta_k=0.1, neutral=0.5)
                for leg in robot.legs} for k in ks]
    t0 = time.perf_counter()
    for springs in designs:
        analysis = prepared.evaluate(springs)
    t_fast = (time.perf_counter() - t0) / len(designs)

    idx = np.linspace(0, motion.n_samples - 1, args.reference_samples).astype(int)
    tau_s = analysis.tau_spring
    t0 = time.perf_counter()
    f_ref = solve_reference(prepared.system, tau_s, "joule", prepared.weights("joule"),
                            prepared.contact, samples=idx)
    t_ref = (time.perf_counter() - t0) / idx.size * motion.n_samples
    diff = np.max(np.abs(f_ref[idx] - analysis.forces.reshape(motion.n_samples, -1)[idx]))

    print(f"default tripod gait, {motion.n_samples} samples per cycle, objective joule")
    print(f"prepare (once per motion):            {t_prep * 1e3:9.2f} ms")
    print(f"evaluate, fast path (per stiffness):  {t_fast * 1e3:9.2f} ms")
    print(f"cvxpy per sample (per stiffness):     {t_ref * 1e3:9.2f} ms "
          f"(measured on {idx.size} samples)")
    print(f"ratio cvxpy / fast:                   {t_ref / t_fast:9.0f} x")
    print(f"max |f_fast - f_cvxpy|:               {diff:9.2e} N")


if __name__ == "__main__":
    main()
