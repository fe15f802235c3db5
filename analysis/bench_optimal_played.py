"""Why an optimal cycle played as its knots does not walk for what the solver booked, and that
its cycle rebuilt in task space does (issue #56; log:
analysis/bench_logs/bench_optimal_played.log; not an example study: it needs the optimal extra
and minutes).

Run:  python analysis/bench_optimal_played.py --chosen cd.pkl [--nodes 40]

Needs the ``optimal`` extra. G and S from the pickle ``analysis/bench_optimal_rows.py --chosen``
writes (the co-design's gait and springs); the optimal cycle from G with S in its dynamics
(40 knots, 100 iterations), then each figure of docs/optimal.md's "Played as planned": the
solver's own J/m; the force program on its knots (the feedforward the simulation gives them);
the knots simulated (the simulation's cubic Hermite reference of their joint angles, their
semi-implicit velocities as its slopes) under both servos, open loop where the gait allows and
with balance feedback; the same knots with central-difference velocities; how far the Hermite
reference's joints put the stance feet off their footholds and its velocities off the rebuilt
cycle's; the springs' and gravity's work booked by the knots' left Riemann sums over a cycle
(zero for a conservative force in continuous time) and the power at ``v_{k+1}``; the cycle
rebuilt in task space, predicted and simulated.
"""

from __future__ import annotations

import argparse
import os
import pickle
import time

import numpy as np
import pinocchio as pin
from bench_optimal_duty import (  # the script beside this one (analysis/ is on sys.path)
    predicted,
    sims,
)

import hexaleg
from hexaleg.motion.legged import gait
from hexaleg.optimal.periodic import shifted_state
from hexaleg.optimal.problem import OptimalParams, build_problem
from hexaleg.optimal.solve import solve
from hexaleg.simulation.controllers import reference


def central(robot: hexaleg.Robot, knots: hexaleg.Motion) -> hexaleg.Motion:
    """The knots with central-difference velocities ``(q_{k+1} ⊖ q_{k−1}) / 2dt`` and
    accelerations, periodic across the cycle's displacement, no semi-implicit marker."""
    n, dt, nq = knots.n_samples, knots.dt, robot.model.nq
    h = np.asarray(knots.info["cycle"])
    after = shifted_state(np.concatenate([knots.q[0], knots.v[0]]), h)[:nq]
    before = shifted_state(np.concatenate([knots.q[-1], knots.v[-1]]), np.linalg.inv(h))[:nq]
    q = np.vstack([before, knots.q, after])
    v = np.array([pin.difference(robot.model, q[k], q[k + 2]) / (2 * dt) for k in range(n)])
    wrapped = np.vstack([v[-1:], v, v[:1]])
    a = (wrapped[2:] - wrapped[:-2]) / (2 * dt)
    info = {k: x for k, x in knots.info.items() if k != "integrator"}
    return hexaleg.Motion(t=knots.t, q=knots.q, v=v, a=a, stance=knots.stance, feet=knots.feet,
                          period=knots.period, distance=knots.distance, info=info)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--chosen", required=True, help="pickle of G and S")
    parser.add_argument("--nodes", type=int, default=40, help="knots of the optimal cycle")
    args = parser.parse_args()
    t0 = time.perf_counter()
    with open(args.chosen, "rb") as f:
        saved = pickle.load(f)
    run = hexaleg.Scenario.load("hexaleg")
    robot, motor, contact = run.model, run.actuator, run.contact
    springs = saved["springs"]
    built = build_problem(robot, gait(robot, saved["chosen"]), motor, springs,
                          OptimalParams(nodes=args.nodes))
    r = solve(robot, built, say=lambda line: print(f"  {line}", flush=True), every=20)
    knots, rebuilt, d = r.motion, r.task_space, r.motion.distance
    print(f"solver's own: {r.energy_per_metre:.3f} J/m ({r.iterations} iterations, "
          f"stationarity {r.stationarity:.2g}, stance slip {r.slip:.3g} m/s, drift "
          f"{r.drift:.2g} m)", flush=True)
    print(f"force program on the knots: "
          f"{predicted(robot, knots, motor, springs, contact)}", flush=True)
    print("knots simulated: " + sims(robot, knots, motor, springs, contact), flush=True)
    c = central(robot, knots)
    print(f"knots with central-difference velocities: "
          f"{predicted(robot, c, motor, springs, contact)} predicted, "
          "simulated " + sims(robot, c, motor, springs, contact), flush=True)
    ref = reference(knots, np.zeros((knots.n_samples, robot.nj)), rebuilt.t)
    off = 0.0
    for k in range(rebuilt.n_samples):
        q = rebuilt.q[k].copy()
        q[7:] = ref.q[k]
        pin.framesForwardKinematics(robot.model, robot.data, q)
        for j, leg in enumerate(robot.legs):
            if rebuilt.stance[k, j]:
                off = max(off, float(np.linalg.norm(
                    robot.data.oMf[leg.foot_frame_id].translation - rebuilt.feet[k, j])))
    print(f"the Hermite reference on the rebuilt base: stance feet up to {off * 1e3:.2f} mm off "
          f"their footholds; joint velocities up to {np.abs(ref.qdot - rebuilt.v[:, 6:]).max():.2f}"
          f" rad/s off the rebuilt cycle's (largest {np.abs(rebuilt.v[:, 6:]).max():.2f})",
          flush=True)
    nq = robot.model.nq
    q, v, u = r.x[:, :nq], r.x[:, nq:], r.torques
    dq = np.array([pin.difference(robot.model, q[k], q[k + 1]) for k in range(len(u))])
    ts = r.spring_torques
    g = np.array([pin.computeGeneralizedGravity(robot.model, robot.data, qk) for qk in q[:-1]])
    trapezoid = 0.5 * (ts + np.roll(ts, -1, axis=0))
    later = built.power.exact(u, v[1:, 6:]).sum() * built.dt / d
    print(f"left Riemann sums over a cycle: springs' work {(ts * dq[:, 6:]).sum():.4f} J "
          f"(trapezoid {(trapezoid * dq[:, 6:]).sum():.1g} J), gravity's "
          f"{-(g * dq).sum():.4f} J; the power at v_(k+1): {later:.3f} J/m", flush=True)
    print(f"rebuilt in task space: "
          f"{predicted(robot, rebuilt, motor, springs, contact)} predicted, "
          "simulated " + sims(robot, rebuilt, motor, springs, contact), flush=True)
    times = os.times()
    print(f"wall {time.perf_counter() - t0:.0f} s, CPU {times.user + times.system:.0f} s",
          flush=True)


if __name__ == "__main__":
    main()
