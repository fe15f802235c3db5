"""A small spring-placement study on hexaleg's default tripod gait: which joint class should carry
a dead-zone spring, on a coarse grid of designs, and which set of classes saves most.

Run:  python analysis/placement_hexaleg.py   (expected output: analysis/logs/placement_hexaleg.log)

The default gait at 200 samples per cycle (as notebook 03), AX-18A servos, minimum-Joule foot
forces; designs ranked by the electrical energy per cycle. Each class (the same spring on all six
legs) is swept alone over k × dead zone × neutral offset:

* the spring is the paper's dead zone (eq. 8): no torque within ±θ_k of its neutral, k per radian
  beyond (eq. 7 convention, α = 1); θ_k is a fraction of each joint's half range of motion in the
  gait and the neutral is the centre of that range (the paper's symmetric assembly, eq. 25) plus
  the offset — an offset dead zone is a preloaded spring, the paper's conclusion 2 ("cannot be
  assembled symmetrically" under gravity);
* designs the force program cannot carry (no admissible forces, a torque over the servo's limit)
  are counted and skipped.

Every set of classes is then evaluated with each class at its best grid design (not re-optimised
jointly). notebook 03 and tests/test_readme.py refine these by Nelder–Mead.
"""

from __future__ import annotations

import itertools

import numpy as np

import hexaleg
from hexaleg.design.rules import centred_springs

CLASSES = ("coxa", "femur", "tibia")
KS = np.geomspace(0.01, 1.0, 5)  # N·m/rad
DEAD_ZONES = (0.25, 0.5, 0.75)  # θ_k / half range of motion
OFFSETS = (-1.0, 0.0, 1.0)  # rad, neutral − centre of the range of motion


def springs(robot, motion, cls, k, dead_zone, offset) -> hexaleg.SpringSet:
    """The design on every joint of ``cls``, dead zone and neutral from its own range."""
    centred = centred_springs(robot, motion, cls, k, dead_zone=dead_zone)
    return hexaleg.SpringSet({j: hexaleg.DeadZoneSpring(stiffness=k, theta_k=s.theta_k,
                                                        neutral=s.neutral + offset)
                              for j, s in centred.items()})


def main() -> None:
    robot = hexaleg.load_robot()
    motion = hexaleg.tripod_gait(robot, hexaleg.GaitParams(samples=200))
    prepared = hexaleg.prepare(robot, motion)
    base = prepared.evaluate().metrics["total"]["electrical"]
    print(f"default gait, {motion.n_samples} samples: {base:.4f} J electrical per cycle without "
          f"springs; grid {len(KS)} k × {len(DEAD_ZONES)} dead zones × {len(OFFSETS)} offsets")
    best: dict[str, tuple[float, tuple, hexaleg.SpringSet]] = {}
    for cls in CLASSES:
        results, skipped = [], 0
        for k, dz, off in itertools.product(KS, DEAD_ZONES, OFFSETS):
            s = springs(robot, motion, cls, float(k), dz, off)
            try:
                e = prepared.evaluate(s).metrics["total"]["electrical"]
            except hexaleg.HexalegError:
                skipped += 1
                continue
            results.append((e, (float(k), dz, off), s))
        centred = min((r for r in results if r[1][2] == 0.0), key=lambda r: r[0])
        best[cls] = min(results, key=lambda r: r[0])
        print(f"\n{cls}: {len(results)} designs evaluated, {skipped} not admissible")
        for tag, (e, (k, dz, off), _) in (("best centred", centred), ("best", best[cls])):
            print(f"  {tag:12s} k = {k:.3g} N·m/rad, θ_k/half range = {dz:.2f}, offset "
                  f"{off:+.1f} rad: {e:.4f} J, saving {100 * (base - e) / base:+.2f} %")
    print("\nsets of sprung classes (each at its best grid design), best first:")
    rows = []
    for r in range(1, len(CLASSES) + 1):
        for combo in itertools.combinations(CLASSES, r):
            merged = hexaleg.SpringSet({j: sp for c in combo for j, sp in best[c][2].items()})
            rows.append((prepared.evaluate(merged).metrics["total"]["electrical"], combo))
    for e, combo in sorted(rows):
        print(f"  {'+'.join(combo):18s} {e:.4f} J, saving {100 * (base - e) / base:+.2f} %")


if __name__ == "__main__":
    main()
