"""The built-in hexapod simulated in MuJoCo: timestep convergence, both servos, sensitivity.

Run:  python analysis/simulate_hexaleg.py    (expected output: analysis/logs/simulate_hexaleg.log)

The default tripod gait with its servo (AX-18A) and the globally optimal linear springs on the
femurs (``hexaleg simulate``'s study with those springs; plain ``hexaleg simulate`` simulates the
report's answer, on the femurs and tibias), simulated with and without them for 4 cycles, the
last 2 evaluated (``hexaleg.commands.simulate``):

1. timestep convergence, dt = 0.5, 0.25, 0.125 and 0.667 ms, for the feedforward + PD servo and
   the position-only servo: energy per cycle with and without the springs, the saving, the distance;
2. where in the cycle the simulated energy departs from the prediction: the electrical energy
   difference in the 50 ms after each load handover (t = 0 and T/2) and in the rest;
3. the sensitivity table (servo gains ×0.25…×4, ground 4× softer and stiffer, half the friction,
   MuJoCo's no-slip pass, the other controller).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from hexaleg.commands.simulate.study import load_study
from hexaleg.design.search.optimal import optimal_springs
from hexaleg.scenario.scenario import Scenario
from hexaleg.simulation.sensitivity import sensitivity

TIMESTEPS = (5e-4, 2.5e-4, 1.25e-4, 1 / 1500)
"""s: the default, halved twice, and 2/3 ms (the timestep a 50× real-time factor would need:
docs/simulate.md, Speed)."""
HANDOVER = 0.05  # s after each switch of tripods


def where(s) -> str:
    """Electrical energy per cycle, simulated − predicted, in the handover windows and the rest."""
    parts = []
    for run, analysis in ((s.with_springs, s.analysis), (s.baseline, s.baseline_analysis)):
        traj, sim = run.trajectory, run.sim
        steps = round(s.motion.period / sim.timestep)
        window = slice(traj.n - steps, traj.n)
        qdot = traj.qvel[window][:, sim.joints.dof]
        p_sim = analysis.motor.electrical_power(traj.tau_motor[window], qdot).sum(1)
        phase = np.arange(steps) * sim.timestep
        p_pred_samples = analysis.motor.electrical_power(analysis.tau_motor, analysis.qdot).sum(1)
        p_pred = np.interp(phase, s.motion.t, p_pred_samples, period=s.motion.period)
        diff = (p_sim - p_pred) * sim.timestep
        half = s.motion.period / 2
        near = (phase % half) < HANDOVER
        parts.append(f"{run.name} {diff.sum():+.4f} J = {diff[near].sum():+.4f} J in the "
                     f"{HANDOVER * 1e3:.0f} ms after the handovers + {diff[~near].sum():+.4f} J "
                     "in the rest")
    return "; ".join(parts)


def main() -> None:
    study = load_study(Scenario.load("hexaleg"))
    best = optimal_springs(study.prepared, ["femur"], "linear", study.objective)
    study = dataclasses.replace(study, springs=best.springs, design=(
        "the globally optimal linear springs on the femur joints (optimal_springs, "
        f"{study.objective} objective)"))
    spring = next(iter(study.springs.values()))
    print(f"springs: {study.design}: {len(study.springs)} joints, stiffness "
          f"{spring.stiffness:.3g} N·m/rad, torque at reference {spring.torque_at_reference:+.4f}"
          " N·m")
    for controller in ("feedforward", "position"):
        print(f"\n{controller} servo: dt (ms) | electrical with / without springs (J per cycle) | "
              "saving (%) | joule saving (%) | distance per cycle (mm) | tracking RMS (mrad)")
        base = None
        for dt in TIMESTEPS:
            settings = dataclasses.replace(study.settings, controller=controller, timestep=dt)
            s = dataclasses.replace(study, settings=settings).run()
            if base is None:
                base = s
                w, b, saved = s.predicted()
                print(f"  predicted      | {w:.4f} / {b:.4f} | {100 * saved:.2f} | "
                      f"{100 * s.predicted('joule')[2]:.2f} | {s.motion.distance * 1e3:.2f} | 0")
            w, b, saved = s.simulated()
            walk = s.with_springs.walk
            print(f"  {dt * 1e3:<14.3f} | {w:.4f} / {b:.4f} | {100 * saved:.2f} | "
                  f"{100 * s.simulated('joule')[2]:.2f} | {walk.distance_per_cycle * 1e3:.2f} | "
                  f"{walk.tracking_rms * 1e3:.3f}")
        print(f"  at {TIMESTEPS[0] * 1e3:g} ms, simulated − predicted: {where(base)}")
        print("  sensitivity: variant | verdict | simulated saving (%) | electrical with / "
              "without (J) | distance (mm)")
        for row in sensitivity(base):
            if row["simulated"] is None:
                print(f"    {row['label']:<24} | {row['verdict']}")
                continue
            print(f"    {row['label']:<24} | {row['verdict']} ({row['controller']}) | "
                  f"{100 * row['simulated']:.2f} | {row['electrical']:.4f} / "
                  f"{row['baseline']:.4f} | {row['distance_per_cycle'] * 1e3:.2f}")


if __name__ == "__main__":
    main()
