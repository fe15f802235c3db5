"""Logs no one here wrote: a MuJoCo walk of the built-in hexapod read back as a robot's log.

Run:  python analysis/logged_hexaleg.py    (expected output: analysis/logs/logged_hexaleg.log)

The default tripod gait (AX-18A servos, feedforward + PD) simulated in MuJoCo after a 2 cm drop
and a 1 s stand, then 10 cycles (:func:`hexaleg.simulation.walk_log.walk_log`), logged at 100 Hz
and at 500 Hz (joints in degrees) through a sensor model: encoders quantised to a Dynamixel tick
(0.29°) after noise of half a tick, a motion-capture base with 0.5 mm noise, an IMU attitude
with 0.2° noise. Each log is read four ways — full pose + joints, joints +
IMU quaternion, joints alone, and the pose with contact switches (``contact_<LEG>``: the
simulated contact force non-zero) — by ``hexaleg.load_motion`` (cycle found and averaged from the
steady part; stance from the feet's kinematics; base from the log or leg odometry), and the
electrical energy per cycle of the read motion (minimum-Joule forces, no springs) is set beside
the simulation's own over its last 6 cycles (issue #38: within 4 % with the pose, 6 % with
joints + IMU). Touch: each foot's fraction of the cycle on the ground, read (low and still)
against simulated (contact force non-zero), the largest difference over the legs; stance: the
load-bearing fraction the forces use, against the gait's duty factor 0.5. Residual: samples
whose logged base motion the contacts could not produce (nearest forces, their largest residual
force as a fraction of the weight).
"""

from __future__ import annotations

import tempfile
import warnings
from pathlib import Path

import numpy as np

import hexaleg
from hexaleg.simulation.walk_log import walk_log

READS = {"pose + joints": ("joints", "base", "imu"), "joints + IMU": ("joints", "imu"),
         "joints alone": ("joints",), "+ contacts": ("joints", "base", "imu", "contacts")}


def main() -> None:
    robot = hexaleg.load()
    gait = hexaleg.gait(robot)
    with tempfile.TemporaryDirectory() as tmp:
        for rate in (100.0, 500.0):
            walk = walk_log(robot, gait, rate=rate)
            touch = np.array(list(walk.touch.values()))
            print(f"{rate:.0f} Hz log, {len(walk.columns['time'])} rows: walking from "
                  f"t = {walk.walk_from:.2f} s, simulated electrical {walk.electrical:.3f} J per "
                  f"cycle, feet on the ground {touch.min():.2f}–{touch.max():.2f} of the cycle")
            print("  read          | steady from (s) | cycles | electrical (J) | vs simulated"
                  " | touch, worst leg | stance | residual")
            for label, parts in READS.items():
                path = walk.write(Path(tmp) / f"{rate:.0f}.csv", parts, degrees=rate > 200)
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")  # the residual is printed below
                    motion = hexaleg.load_motion(robot, path)
                    prepared = hexaleg.prepare(robot, motion)
                e = prepared.evaluate(None, "joule").metrics["total"]["electrical"]
                q = motion.info["report"]
                worst = max(abs(q.touch_fractions[leg] - walk.touch[leg]) for leg in walk.touch)
                stance = np.array(list(q.stance_fractions.values()))
                res = prepared.residual
                residual = ("none" if res is None or not len(res.samples) else
                            f"{len(res.samples)} samples, at most "
                            f"{100 * res.fraction.max():.0f} % of the weight")
                print(f"  {label:13s} | {q.steady_from:15.2f} | {q.cycles:6d} | "
                      f"{e:14.3f} | {100 * (e / walk.electrical - 1):+11.1f} % | "
                      f"{worst:16.2f} | {stance.min():.2f}–{stance.max():.2f} | {residual}")


if __name__ == "__main__":
    main()
