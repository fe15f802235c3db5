"""Issue #56: why the landing leg's servo-effort cost (``OptimalParams.servo_landing_weight``)
helps the hexapod's optimal motion under position servos and hurts Solo-12's unsprung trot (log:
analysis/bench_logs/bench_optimal_landing.log; a probe, not an example study: it needs the
optimal extra and minutes).

Run:  python analysis/bench_optimal_landing.py --codesign DIR/codesign.json --robot NAME
                                               --speed V [--weights 0 30] [--timesteps 0 1e-4]

Needs the ``optimal`` extra. From a kept ``hexaleg codesign --motion optimal`` run's chosen
gait (``gait.parameters`` of its JSON), the optimal motion *without springs* (the command's row
3: one box-FDDP solve, :func:`hexaleg.optimal.solve.solve`, with the command's
:class:`~hexaleg.optimal.problem.OptimalParams` on the floor's μ and friction margin) is solved
for each landing weight W, rebuilt in task space, predicted by the rows' judge
(:func:`~hexaleg.design.codesign.alternation.judged`) and taken apart:

* the plan: the solver's J/m, stationarity and friction use at its knots; the landing legs'
  servo effort ``u + D q̇`` at their last swing knot (RMS over the touch-downs, N·m: what the
  cost weighs; ``D`` the motors' back-EMF damping,
  :func:`~hexaleg.optimal.servo_effort.back_emf_damping`) beside the motors' stall torque, and
  the same effort divided by it (a dimensionless lag); the rebuilt cycle's foot speed over the
  last sample before each touch-down (the landing's hardness, m/s); the base's forward speed's
  spread (max − min, m/s: a surge) and its largest yaw rate (rad/s);
* each simulation (:func:`hexaleg.simulation.run.simulate`, ``feedback = "auto"`` as the rows,
  under each servo, at each ``--timesteps`` value, 0 for the automatic one): J/m walked, the
  distance per cycle over the plan's, RMS tracking error, the feet's mean slip a stance, and
  the simulated base's forward-speed spread and largest yaw rate (over the evaluated window).

What it answers: does the weighted plan land harder, surge or yaw, drive the friction cone, or
is the simulation's figure fragile (it moves with the timestep)?
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import os
import time
from typing import Any

import numpy as np

import hexaleg
from hexaleg.design.codesign.alternation import judged
from hexaleg.design.codesign.build import default_gait, floor_constraints
from hexaleg.motion.legged import gait
from hexaleg.optimal.problem import OptimalParams, build_problem
from hexaleg.optimal.servo_effort import back_emf_damping
from hexaleg.optimal.solve import solve
from hexaleg.robot.springs import SpringSet
from hexaleg.simulation.run import Settings, simulate

KEYS = ("period", "duty_factor", "step_height", "body_height", "foot_radius")
"""The gait's searched parameters read from ``codesign.json``."""


def landing_effort(result: Any, stance: np.ndarray, damping: np.ndarray, stall: np.ndarray,
                   columns: list[np.ndarray], nq: int) -> tuple[np.ndarray, np.ndarray]:
    """``u + D q̇`` of each landing leg's joints at its last swing knot, N·m, and the same over
    the joints' stall torque, each one value a joint and touch-down, shape (m,): the
    servo-effort cost's residual (:class:`~hexaleg.optimal.servo_effort.ServoEffortCost`) on the
    solver's knots (``result.torques`` (K, nu), ``result.x`` (K + 1, nq + nv), ``stance``
    (K, legs))."""
    knots = len(result.torques)
    effort, lag = [], []
    for k in range(knots):
        following = (k + 1) % knots
        for j, cols in enumerate(columns):
            if not stance[k, j] and stance[following, j]:
                qdot = result.x[k, nq + 6:]
                e = result.torques[k, cols] + damping[cols] * qdot[cols]
                effort.append(e)
                lag.append(e / stall[cols])
    return np.concatenate(effort), np.concatenate(lag)


def touchdown_speed(motion: Any) -> float:
    """The largest foot speed over the last sample before a touch-down of the motion, m/s
    (``motion.feet`` (T, legs, 3), ``motion.stance`` (T, legs))."""
    dt = float(motion.t[1] - motion.t[0])
    speed = np.linalg.norm(np.diff(motion.feet, axis=0), axis=2) / dt  # (T - 1, legs)
    lands = ~motion.stance[:-1] & motion.stance[1:]
    return float(speed[lands].max()) if lands.any() else 0.0


def base_motion(vx: np.ndarray, yaw_rate: np.ndarray) -> str:
    """The base's forward-speed spread (max − min) and largest |yaw rate|, as text."""
    return (f"forward speed {vx.min():.3f} to {vx.max():.3f} m/s (spread {np.ptp(vx):.3f}), "
            f"yaw rate up to {np.abs(yaw_rate).max():.3f} rad/s")


def simulated(robot: Any, motion: Any, motor: Any, contact: Any, controller: str,
              timestep: float | None) -> str:
    """``motion`` without springs simulated under ``controller`` at ``timestep`` (None: the
    automatic one), as text: J/m, distance, tracking, slip, the base's surge and yaw."""
    sim = simulate(robot, motion, motor, SpringSet(),
                   Settings(controller=controller, feedback="auto", force_samples=0,
                            timestep=timestep), contact=contact)
    run = sim.with_springs
    walk = run.walk
    head = f"{controller:11s} dt {'auto' if timestep is None else f'{timestep:g} s'}: "
    if walk is None:
        return head + f"{run.verdict}: {run.message}"
    traj = run.trajectory
    window = traj.t >= traj.t[-1] - 2 * motion.period  # the evaluated window (2 cycles)
    vx, yaw = traj.qvel[window, 0], traj.qvel[window, 5]
    planned = motion.distance
    figure = (f"{run.metrics['electrical'] / walk.distance_per_cycle:.2f} J/m" if run.walks
              else f"{run.verdict}")
    return (head + f"{figure} ({'balance feedback' if run.feedback else 'open loop'}), "
            f"distance {walk.distance_per_cycle / planned:.3f} of the plan, tracking "
            f"{1e3 * walk.tracking_rms:.0f} mrad RMS, slip {1e3 * walk.slip_mean:.2f} mm a "
            f"stance; {base_motion(vx, yaw)}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--codesign", required=True, help="a hexaleg codesign run's JSON")
    parser.add_argument("--robot", default="hexaleg", help="the registered robot")
    parser.add_argument("--speed", type=float, default=0.06, help="m/s, the run's speed")
    parser.add_argument("--weights", type=float, nargs="+", default=[0.0, 30.0],
                        help="OptimalParams.servo_landing_weight values")
    parser.add_argument("--timesteps", type=float, nargs="+", default=[0.0, 1e-4],
                        help="simulation timesteps, s (0: the automatic one)")
    args = parser.parse_args()
    t0, c0 = time.perf_counter(), os.times()
    run = hexaleg.Scenario.load(args.robot)
    robot, motor = run.model, run.actuator
    c = floor_constraints(run)
    contact = c.contact()
    with open(args.codesign, encoding="utf-8") as f:
        kept = json.load(f)
    found = kept["gait"]["parameters"]
    g = dataclasses.replace(default_gait(robot, args.robot, args.speed, None, 200),
                            **{k: found[k]["value"] for k in KEYS})
    played = gait(robot, g)
    nu = robot.model.nv - 6
    damping = back_emf_damping(motor, nu)
    stall = np.broadcast_to(np.asarray(motor.stall_torque, dtype=float), (nu,))
    columns = [np.asarray(leg.columns) for leg in robot.legs]
    print(f"{args.robot} at {args.speed:g} m/s, gait: duty factor {g.duty_factor:.4g}, period "
          f"{g.period:.6g} s; back-EMF damping D {damping.min():.4g} to {damping.max():.4g} "
          f"N·m·s/rad, stall torque {stall.min():.4g} to {stall.max():.4g} N·m; planned "
          f"(the gait): {base_motion(played.v[:, 0], played.v[:, 5])}", flush=True)
    for w in args.weights:
        params = OptimalParams(mu=contact.mu, friction_use=c.friction_margin,
                               servo_landing_weight=w)
        problem = build_problem(robot, played, motor, SpringSet(), params)
        result = solve(robot, problem)
        said = judged(robot, result, played, motor, SpringSet(), contact, c.friction_margin)
        print(f"-- no springs, servo_landing_weight {w:g}: solver {result.energy_per_metre:.3f} "
              f"J/m at its knots ({result.iterations} iterations, stationarity "
              f"{result.stationarity:.2g}, friction use {result.friction_use:.2f}, slip "
              f"{1e3 * result.slip:.1f} mm/s); predicted rebuilt "
              + ("—" if said.value is None else f"{said.value:.3f} J/m") + " (friction use "
              + ("—" if said.friction_use is None else f"{said.friction_use:.2f}")
              + ("" if said.within else ", beyond the margin") + ")", flush=True)
        stance = np.asarray(result.motion.stance[:len(result.torques)], dtype=bool)
        effort, lag = landing_effort(result, stance, damping, stall, columns, robot.model.nq)
        print(f"   plan: landing effort u + D q̇ at the last swing knot "
              f"{np.sqrt(np.mean(effort ** 2)):.3f} N·m RMS (largest "
              f"{np.abs(effort).max():.3f}; over the stall torque "
              f"{np.sqrt(np.mean(lag ** 2)):.3f} RMS)", flush=True)
        motion = result.task_space
        if motion is None:
            print(f"   not rebuilt: {result.unbuilt}", flush=True)
            continue
        print(f"   plan (rebuilt): touch-down foot speed up to {touchdown_speed(motion):.3f} "
              f"m/s; {base_motion(motion.v[:, 0], motion.v[:, 5])}", flush=True)
        for controller in ("feedforward", "position"):
            for dt in args.timesteps:
                print("   " + simulated(robot, motion, motor, contact, controller,
                                        dt if dt > 0 else None), flush=True)
    c1 = os.times()
    print(f"wall {time.perf_counter() - t0:.0f} s, CPU "
          f"{(c1.user - c0.user) + (c1.system - c0.system):.0f} s", flush=True)


if __name__ == "__main__":
    main()
