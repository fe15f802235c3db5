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
5. Balance feedback (#54, :mod:`hexaleg.simulation.balance`): the default robot's gait with
   its springs stepped closed loop against open loop, alternately in this process, both
   controllers: the controller's cost as a ratio of the open-loop step, of the stepping
   thread's CPU time (a ratio the machine's load leaves alone) and of the wall time. Target ≤ 3×.
6. MuJoCo's stage timers (:mod:`hexaleg.simulation.timers`): the default robot's run with its
   springs stepped with the timers on (as MuJoCo's Python bindings leave them) and off (as a run
   steps), alternately in this process: CPU per step and the ratio, and whether the states are
   the same to the bit.
7. Per robot: the default robot's tripod and the four registered quadrupeds' trots of #54
   (position-only servo, ``[contact] mu = 1``; Solo-12 0.4 s 0.12 m, A1 0.4 s 0.20 m, ANYmal
   0.6 s 0.30 m, Go2 its own), and the test biped's and humanoid's ZMP walks (tests/data,
   feedforward + PD servo), open and closed loop: real-time factor (wall, and per CPU second of
   the stepping), the controller's cost per step against the open-loop step (CPU, the run with
   the springs), verdicts, and the simulated electrical saving against the predicted one
   (``--robots`` skips it with none).
Best of three runs for 1–3; timings depend on the machine and its load, so the benchmark prints
its own CPU share: on the 2-core machine, two other busy processes halve every factor (time
slicing), while one leaves them unchanged; the CPU-time factors and ratios hold either way.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from hexaleg.commands.simulate.study import load_study
from hexaleg.robot.springs import DeadZoneSpring, PreloadedSpring, SpringSet
from hexaleg.scenario.scenario import Scenario
from hexaleg.simulation.run import simulate, simulate_run

TROTS = {"solo12": (0.4, 0.12), "a1": (0.4, 0.20), "anymal": (0.6, 0.30), "go2": None}
"""#54's trots: robot → (period s, stride m), or None for the robot's own trot."""
DATA = Path(__file__).resolve().parents[1] / "tests" / "data"
BIPEDS = {"biped": DATA / "biped.toml", "humanoid": DATA / "humanoid.toml"}
"""The test robots on two point feet (their own ZMP walk; #54: "bipeds walk their ZMP gait the
same way")."""

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
    parser.add_argument("--robots", default="hexaleg,solo12,a1,anymal,go2,biped,humanoid",
                        help="robots of row 7, comma-separated ('' to skip it)")
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
        timing = json.loads((Path(out) / "simulate.json").read_text())["timing"]
    print(f"hexaleg simulate (default robot, fresh process): {wall:.1f} s wall (target ≤ 30 s); "
          f"its simulate.json: {timing['text']}")
    feedback_cost(study, settings)
    timers_cost(study, settings)
    if args.robots:
        per_robot(args.robots.split(","))


def feedback_cost(study, settings) -> None:
    """Row 5: the balance controller's cost against the open-loop step, same model, same run,
    alternating (best of three each)."""
    from hexaleg.simulation.model import build_model

    p = study.prepared
    print("balance feedback on the default robot (same model, alternating, best of 3):")
    for controller in ("feedforward", "position"):
        st = dataclasses.replace(settings, controller=controller).sized(p.robot.mass)
        sim = build_model(p.robot, p.motion, p.motor, springs=study.springs, servo=st.servo(),
                          ground=st.ground(p.contact.mu), timestep=5e-4)
        a = p.evaluate(study.springs)
        walls: dict[bool, list[float]] = {False: [], True: []}
        cpus: dict[bool, list[float]] = {False: [], True: []}
        energy: dict[bool, float] = {}
        for _ in range(3):
            for closed in (False, True):
                r = simulate_run("springs", sim, p.motion, a, st, closed)
                walls[closed].append(r.wall / r.trajectory.n)
                cpus[closed].append(r.cpu / r.trajectory.n)
                energy[closed] = r.metrics["electrical"]
        ratio = min(cpus[True]) / min(cpus[False])
        print(f"  {controller:<12} open {min(cpus[False]) * 1e6:5.1f} µs/step, closed "
              f"{min(cpus[True]) * 1e6:5.1f} µs/step of CPU: ratio {ratio:.2f}× (target ≤ 3×; "
              f"of wall time {min(walls[True]) / min(walls[False]):.2f}×); "
              f"energy closed/open {energy[True] / energy[False] - 1:+.2%}")


def timers_cost(study, settings) -> None:
    """Row 6: the stepping with MuJoCo's stage timers on against off, same model, alternating
    (best of five each, the stepping thread's CPU time)."""
    import contextlib

    from hexaleg.simulation import stepping, timers
    from hexaleg.simulation.controllers import controls, reference
    from hexaleg.simulation.model import build_model

    p = study.prepared
    st = settings.sized(p.robot.mass)
    sim = build_model(p.robot, p.motion, p.motor, springs=study.springs, servo=st.servo(),
                      ground=st.ground(p.contact.mu), timestep=5e-4)
    t = np.arange(round(st.cycles * p.motion.period / sim.timestep)) * sim.timestep
    ctrl = controls(sim.servo, reference(p.motion, p.evaluate(study.springs).tau_motor, t),
                    sim.kp, sim.kd)
    start = sim.joints.to_mujoco(p.motion.q[0], p.motion.v[0])
    height = float(np.mean(p.motion.q[:, 2]))
    cpu: dict[bool, list[float]] = {False: [], True: []}
    runs = {}
    try:
        for _ in range(5):
            for timed in (True, False):
                stepping.untimed = contextlib.nullcontext if timed else timers.untimed
                clock = time.thread_time()
                runs[timed] = stepping.run(sim, ctrl, *start, height)
                cpu[timed].append((time.thread_time() - clock) / runs[timed].n)
    finally:
        stepping.untimed = timers.untimed
    same = all(np.array_equal(getattr(runs[True], f), getattr(runs[False], f))
               for f in ("qpos", "qvel", "servo", "feet"))
    on, off = min(cpu[True]), min(cpu[False])
    print(f"MuJoCo's stage timers (default robot, its springs, alternating, best of 5): on "
          f"{on * 1e6:5.2f} µs/step, off {off * 1e6:5.2f} µs/step of CPU: off/on {off / on:.3f}; "
          f"the states {'the same to the bit' if same else 'DIFFER'}")


def per_robot(robots: list[str]) -> None:
    """Row 7: real-time factors open and closed loop, verdicts, simulated vs predicted saving."""
    print("per robot (4 cycles, the last 2 evaluated; rtf: simulated s per wall s of both runs' "
          "stepping, and per CPU s; cost: CPU per step closed / open, the run with springs):")
    print(f"  {'robot, gait, servo':<34} {'loop':<6} {'rtf':>6} {'rtf cpu':>7} {'cost':>5}  "
          f"{'springs / baseline':<22} {'predicted':>9} {'simulated':>9}")
    for robot in robots:
        if robot == "hexaleg":
            text, label = "", "hexaleg tripod, position"
        elif robot in BIPEDS:
            text, label = '[simulate]\ncontroller = "feedforward"\n', f"{robot} ZMP walk, ff + PD"
        else:
            gait = TROTS[robot]
            text = '[gait]\npattern = "trot"\n' + (
                f"period = {gait[0]}\nstride_length = {gait[1]}\n" if gait else "") + \
                '[contact]\nmu = 1\n'
            label = f"{robot} trot, position"
        with tempfile.TemporaryDirectory() as where:
            config = Path(where) / "run.toml"
            config.write_text(text if robot in BIPEDS else
                              text + '[simulate]\ncontroller = "position"\n')
            study = load_study(Scenario.load(str(BIPEDS.get(robot, robot)), config))
        open_step = None
        for feedback in ("off", "on"):
            s = dataclasses.replace(study, settings=dataclasses.replace(
                study.settings, feedback=feedback, force_samples=0)).run()
            runs = (s.with_springs, s.baseline)
            simulated_time = sum(r.simulated_time for r in runs)
            rtf = simulated_time / s.stepping_wall  # side by side: their spans' union
            per_cpu = simulated_time / sum(r.cpu for r in runs)
            step = s.with_springs.cpu / s.with_springs.trajectory.n
            open_step = open_step or step
            verdicts = " / ".join(r.verdict for r in runs)
            simulated = f"{s.simulated()[2]:+.2%}" if s.walks else "—"
            print(f"  {label:<34} {'closed' if feedback == 'on' else 'open':<6} {rtf:5.1f}× "
                  f"{per_cpu:6.1f}× {step / open_step:4.2f}×  {verdicts:<22} "
                  f"{s.predicted()[2]:+9.2%} {simulated:>9}", flush=True)


if __name__ == "__main__":
    main()
