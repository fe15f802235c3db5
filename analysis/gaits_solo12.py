"""Solo-12's gaits: energy per metre and cost of transport vs speed, on level ground and on ±10°
slopes, without springs and with the recommended knee springs.

Run:  python analysis/gaits_solo12.py        (expected output: analysis/logs/gaits_solo12.log)

Solo-12 (ODRI, example-robot-data) with its registry gait (stride 0.08 m, step height 0.04 m)
walks the statically stable crawl (β = ⅘, the body shifted over its support triangles with the
default margin, ``hexaleg.motion.shift``) at periods 4, 2 and 1.33 s (0.02, 0.04, 0.06 m/s), and
trots and paces (β = ½, balanced by the lateral sway, ``hexaleg.motion.balance``) at 1, 0.5 and
0.33 s (0.08, 0.16, 0.24 m/s); 100 samples per cycle; straight up, on and down a 10° slope (body
parallel to the ground). Friction μ = 1 (the pace sways its body across the 0.3 m between its
feet from 0.19 m up: ~0.8 at the switches) and no torque limits (the catalogue's ODRI motor
figures are nominal). Per gait (``hexaleg.design.studies.gaits.gait_energy``): the electrical energy
per metre without springs and with the preloaded knee springs of ``hexaleg.optimal_springs``
(least Joule loss; one design for the front knees and one for the hind knees, which bend the
other way), the cost of transport E / (m g d) (eq. 23), the saving.
"""

from __future__ import annotations

import math

import hexaleg
from hexaleg.design.studies.gaits import gait_energy, table_header, table_line
from hexaleg.motion.scaling import robot_gait

ROBOT = "solo12"
GAITS = (("crawl", (4.0, 2.0, 4.0 / 3.0)), ("trot", (1.0, 0.5, 1.0 / 3.0)),
         ("pace", (1.0, 0.5, 1.0 / 3.0)))
SLOPES = (-10.0, 0.0, 10.0)  # deg
SAMPLES = 100
CONTACT = hexaleg.ContactParams(mu=1.0, torque_limits=False)
KNEES = {"front": ["FL_KFE", "FR_KFE"], "hind": ["HL_KFE", "HR_KFE"]}
"""One design per knee pair: Solo's front and hind knees bend opposite ways."""


def main() -> None:
    robot = hexaleg.load(ROBOT)
    base = robot_gait(ROBOT)
    print(f"{ROBOT}: {robot.mass:.4g} kg, knee springs (preloaded; front and hind pairs), "
          f"{SAMPLES} samples, μ = {CONTACT.mu:g}")
    print(table_header("gait"))
    for pattern, periods in GAITS:
        for period in periods:
            for slope in SLOPES:
                gait = base.updated({"pattern": pattern, "period": period, "samples": SAMPLES,
                                     "slope": math.radians(slope)})
                print(table_line(gait_energy(robot, gait, KNEES, contact=CONTACT)))


if __name__ == "__main__":
    main()
