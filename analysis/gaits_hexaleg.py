"""The hexapod's gait patterns: energy per metre and cost of transport vs speed, on level ground
and on ±10° slopes, without springs and with the recommended femur springs.

Run:  python analysis/gaits_hexaleg.py       (expected output: analysis/logs/gaits_hexaleg.log)

The built-in hexapod walks the tripod (β = ½), ripple (⅔) and wave (⅚) patterns
(``hexaleg.motion.patterns``; McGhee & Frank 1968) with its default stride (0.06 m) at three
periods (2, 1 and 0.75 s: 0.03, 0.06 and 0.08 m/s), 100 samples per cycle, straight up, on and
down a 10° slope (body parallel to the ground, ``hexaleg.motion.ground``). Per gait
(``hexaleg.design.studies.gaits.gait_energy``): the AX-18A servos' electrical energy per metre
travelled along the ground without springs, and with the preloaded femur springs that
``hexaleg.optimal_springs`` finds for that gait (the global optimum of their magnitudes for
least Joule loss); the cost of transport E / (m g d) (eq. 23) of both; the saving.
"""

from __future__ import annotations

import math

import hexaleg
from hexaleg.design.studies.gaits import gait_energy, table_header, table_line

PATTERNS = ("tripod", "ripple", "wave")
PERIODS = (2.0, 1.0, 0.75)  # s, stride 0.06 m
SLOPES = (-10.0, 0.0, 10.0)  # deg
SAMPLES = 100


def main() -> None:
    robot = hexaleg.load()
    print(f"hexaleg: {robot.mass:.4g} kg, femur springs (preloaded), {SAMPLES} samples")
    print(table_header("pattern"))
    for pattern in PATTERNS:
        for period in PERIODS:
            for slope in SLOPES:
                gait = hexaleg.GaitParams(pattern=pattern, period=period, samples=SAMPLES,
                                          slope=math.radians(slope))
                print(table_line(gait_energy(robot, gait, ["femur"])))


if __name__ == "__main__":
    main()
