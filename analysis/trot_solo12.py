"""Solo-12's trot: mechanical energy per joint class, and what centred knee springs do to it.

Run:  python analysis/trot_solo12.py         (expected output: analysis/logs/trot_solo12.log)

Solo-12 (ODRI) from example-robot-data through ``hexaleg.load("solo12")``, trotting with its
registry gait (``robot_gait("solo12")``: period 0.5 s, duty factor 0.6,
stride 0.08 m, diagonal pairs) at 200 samples per cycle (as notebook 04). A two-foot stance cannot
push a moment about the line through its feet, so the gait sways the body (linear inverted pendulum,
Kajita et al., ICRA 2003, refined on the exact RNEA moment; docs/robots.md). Foot forces from the
minimum-Joule program; the servo catalogue's torque limits are for small robots and are off.

Metrics per cycle (``metrics``, docs/energy.md): positive work ∫ max(0, τ q̇) dt (what
motors that cannot recover energy must supply; the paper's E of eq. 20 taken as positive work),
peak and RMS torque. The knee springs are the paper's dead zone (eq. 8) centred on each knee's
range of motion with θ_k/A = 7.32°/0.3 rad (Section 4.2, eq. 25), eq. 7 convention, α = 1
(``hexaleg.design.rules.centred_springs``), stiffness swept on a log grid.
"""

from __future__ import annotations

import dataclasses

import numpy as np

import hexaleg
from hexaleg.design.rules import centred_springs
from hexaleg.motion.scaling import robot_gait
from hexaleg.robot.registry import DESCRIPTIONS

ROBOT = "solo12"
KS = np.geomspace(0.01, 10.0, 7)  # N·m/rad


def main() -> None:
    desc = DESCRIPTIONS[ROBOT]
    robot = hexaleg.load(ROBOT)
    gait = dataclasses.replace(robot_gait(ROBOT), samples=200)
    motion = hexaleg.gait(robot, gait)
    prepared = hexaleg.prepare(robot, motion, contact=hexaleg.ContactParams(torque_limits=False))
    rigid = prepared.evaluate().metrics
    g = motion.info["balance"]
    print(f"{ROBOT}: {robot.nj} joints, {robot.mass:.4g} kg; trot: period {motion.period:.4g} s, "
          f"{motion.n_samples} samples, speed {motion.info['speed']:.4g} m/s, body sway "
          f"±{1e3 * g['amplitude']:.3g} mm")
    names = list(rigid["joint_names"])
    print(f"\n{'without springs':18s} {'E+ [J]':>9s} {'peak [N·m]':>11s}")
    for cls in desc.joint_kinds:
        cols = [names.index(j) for j in robot.joints(cls)]
        e = float(np.sum(rigid["joint"]["positive_work"][cols]))
        peak = float(np.max(rigid["joint"]["peak_torque"][cols]))
        print(f"  {cls:5s} ({len(cols)} joints) {e:9.4f} {peak:11.4f}")
    total = rigid["total"]
    print(f"  {'all':16s} {total['positive_work']:9.4f} {total['peak_torque']:11.4f}")
    print(f"\ncentred springs on the {desc.spring_class} joints, savings [%]:")
    print(f"  {'k [N·m/rad]':>11s} {'E+':>7s} {'RMS':>7s} {'peak':>7s}")
    for k in KS:
        springs = centred_springs(robot, motion, desc.spring_class, float(k))
        s = prepared.evaluate(springs).savings["total"]
        print(f"  {k:11.4g} {100 * s['positive_work']:+7.2f} {100 * s['rms_torque']:+7.2f} "
              f"{100 * s['peak_torque']:+7.2f}")


if __name__ == "__main__":
    main()
