"""Whether Solo-12's optimal trots' simulated energy is the servos' or the simulation's sensitivity
(issue #56's quadruped row; log: analysis/bench_logs/bench_optimal_trot_timestep.log; not an
example study: it needs the optimal extra and minutes).

Run:  python analysis/bench_optimal_trot_timestep.py --chosen cd.pkl

Needs the ``optimal`` extra. The four rows of ``analysis/bench_optimal_rows.py --robot solo12
--speed 0.3 --grouping mirrored`` from the co-design's gait and springs in the pickle it writes
(the same call: 40 knots, 100 iterations, one alternation round, so the same motions), then each
row's motion simulated with balance feedback (``feedback = "auto"``: every trot closed loop)
under both servos at the automatic timestep and at 0.2 and 0.1 ms. With balance feedback the
two servos are one loop: the same actuator (``kp``, ``kd = D``, ``±τ_s``), the same controller,
and references that differ by ``kd q̇*/kp`` alone (:func:`hexaleg.simulation.controllers.
controls`), so a figure that moves with the timestep more than between the servos is the
simulation's sensitivity, not a servo's bill. Printed per run: J/m walked (or the verdict), the
share of the planned swing samples whose foot the ground pushes (> 0.05 N: scuffing), the peak
ground force in the first 30 ms of a stance (the touchdown's impact), and per motion the plan's
largest friction use (the force program at the floor's μ, the feedforward the servos get) and
its swing feet's least apex over the floor. Then the same runs with the swing feet aimed at
their planned footholds (``foot_placement.FEWEST_PLACED`` raised past a trot's two stance feet:
the balance controller's law for the feet it does not place, :mod:`hexaleg.simulation.balance`,
"Footholds"; Raibert's placement off), to tell the placement's share.
"""

from __future__ import annotations

import argparse
import os
import pickle
import time

import numpy as np

import hexaleg
from hexaleg.design.chain.groups import design_groups
from hexaleg.design.codesign.build import default_gait
from hexaleg.design.codesign.optimal_rows import optimal_rows
from hexaleg.dynamics.prepare import prepare
from hexaleg.motion.legged import gait
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.model import Robot
from hexaleg.robot.springs import SpringSet
from hexaleg.simulation import foot_placement, measures
from hexaleg.simulation.run import Settings, simulate

TIMESTEPS = (None, 2e-4, 1e-4)
"""The automatic timestep, then two finer ones, s."""
LOADED = 0.05
"""N: a planned swing foot pushed harder than this by the ground is on it."""
TOUCHDOWN = 0.03
"""s: the first part of a stance whose peak ground force is the touchdown's."""


def stance_age(stance: np.ndarray, dt: float) -> np.ndarray:
    """Per step and leg, the time since the planned stance began (0 in a swing), s;
    ``stance`` (n, n_legs) bool at consecutive steps ``dt`` apart."""
    age = np.zeros(stance.shape)
    for j in range(stance.shape[1]):
        run = 0
        for i in range(len(stance)):
            run = run + 1 if stance[i, j] else 0
            age[i, j] = run * dt
    return age


def run_line(robot: Robot, motion: Motion, motor: object, springs: SpringSet,
             contact: object, controller: str, timestep: float | None) -> str:
    """One simulation of a row's motion with its springs, measured (module docstring)."""
    sim = simulate(robot, motion, motor, springs,
                   Settings(controller=controller, timestep=timestep, force_samples=0),
                   contact=contact)
    r = sim.with_springs
    dt = r.sim.timestep
    head = f"      {controller:11s} dt {dt * 1e3:.3f} ms: "
    if r.walk is None:
        return head + f"{r.verdict}"
    tr = r.trajectory
    steps = round(motion.period / dt)
    rows = np.arange(tr.n - 2 * steps, tr.n - 1)
    stance = motion.stance[measures.planned_index(motion, tr.t[rows])].astype(bool)
    age = stance_age(stance, dt)
    every = rows[::2]
    normal = np.array([measures.contact_forces(r.sim, d)[:, 2]
                       for d in measures.forward_states(r.sim, tr, every)])
    swing, early = ~stance[::2], (stance & (age < TOUCHDOWN))[::2]
    verdict = "walks" if r.walks else r.verdict
    return head + (f"{r.metrics['electrical'] / r.walk.distance_per_cycle:6.2f} J/m "
                   f"({verdict}, {r.walk.distance_per_cycle * 1e3:.1f} mm a cycle); swing "
                   f"feet on the ground {np.mean(normal[swing] > LOADED):.3f} of their samples; "
                   f"touchdown peak {normal[early].max():.0f} N")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--chosen", required=True,
                        help="pickle of analysis/bench_optimal_rows.py --chosen (Solo-12's)")
    args = parser.parse_args()
    t0 = time.perf_counter()
    run = hexaleg.Scenario.load("solo12")
    robot = run.model
    with open(args.chosen, "rb") as f:
        saved = pickle.load(f)
    chosen, springs = saved["chosen"], saved["springs"]
    default = dict(saved["rows"])["default gait, no springs"]
    base = default_gait(robot, "solo12", 0.3, None, chosen.samples)
    groups = design_groups(robot, tuple(robot.joint_classes), "mirrored")
    table = optimal_rows(robot, run.actuator, run.contact, base, chosen, springs,
                         (default, saved["per_metre"]), groups=groups, rounds=1)
    print("\n".join(table.lines()), flush=True)
    played = (gait(robot, base), gait(robot, chosen), table.bare.task_space,
              table.alternation.motion)
    fitted = (SpringSet(), springs, SpringSet(), table.springs)
    weight = robot.mass * 9.81
    print(f"each row's motion simulated with balance feedback at the automatic timestep, 0.2 "
          f"and 0.1 ms (weight {weight:.1f} N):", flush=True)
    rows = list(zip(table.rows, played, fitted, strict=True))
    for row, motion, s in rows:
        plan = prepare(robot, motion, motor=run.actuator, contact=run.contact).evaluate(s, "joule")
        on = motion.stance.astype(bool)
        use = np.linalg.norm(plan.forces[..., :2], axis=2) / np.maximum(
            plan.forces[..., 2], 1e-12) / run.contact.mu
        floor = motion.feet[..., 2][on].min()
        apex = [float((motion.feet[:, j, 2][~on[:, j]] - floor).max())
                for j in range(on.shape[1])]
        print(f"    {row.label}: predicted {row.predicted:.2f} J/m; the plan's friction use "
              f"at most {use[on].max():.2f} of μ {run.contact.mu:g}; swing apex "
              f"{min(apex) * 1e3:.1f} to {max(apex) * 1e3:.1f} mm", flush=True)
        for timestep in TIMESTEPS:
            for controller in ("feedforward", "position"):
                print(run_line(robot, motion, run.actuator, s, run.contact, controller,
                               timestep), flush=True)
    print("the same runs with the swing feet aimed at their planned footholds (Raibert's "
          "placement off):", flush=True)
    foot_placement.FEWEST_PLACED = 3  # a trot's two stance feet no longer placed
    for row, motion, s in rows:
        print(f"    {row.label}: predicted {row.predicted:.2f} J/m", flush=True)
        for timestep in TIMESTEPS:
            for controller in ("feedforward", "position"):
                print(run_line(robot, motion, run.actuator, s, run.contact, controller,
                               timestep), flush=True)
    c = os.times()
    print(f"wall {time.perf_counter() - t0:.0f} s, CPU {c.user + c.system:.0f} s", flush=True)


if __name__ == "__main__":
    main()
