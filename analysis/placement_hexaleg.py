"""Spring placement on hexaleg's default tripod gait: for every set of sprung joint classes, the
global optimum of a spring family, and how far the old grid + Nelder–Mead search was from it.

Run:  python analysis/placement_hexaleg.py   (expected output: analysis/logs/placement_hexaleg.log)

The default gait at 200 samples per cycle, AX-18A servos, minimum-Joule foot forces, judged by the
Joule energy per cycle. For each family, :func:`hexaleg.design.studies.placement.placement` designs
the springs of every non-empty set of classes together (the same spring on all six legs of a class;
each class its own design): the magnitudes are the global optimum of the convex program for the
geometry, the contact angles searched (:func:`hexaleg.optimal_springs`).

"old" is the search hexaleg had before: each class alone, a symmetric dead zone (k, θ_k) with
its neutral offset free in ±1 rad (grid + Nelder–Mead, :func:`optimise`), the classes of a
set each at their own optimum. "gap" is the saving the old search left, in points of the
baseline. The dead-zone family contains the old designs, so its gap is never negative. An angle
past which nothing acts (its stiffness and preload 0) prints "—": any angle gives the same spring.
"""

from __future__ import annotations

import hexaleg
import hexaleg.design.families
import hexaleg.design.studies.placement

CLASSES = ("coxa", "femur", "tibia")
FAMILIES = ("dead_zone", "preloaded")
ROUND_OFF = 1e-9  # N·m/rad or N·m: a magnitude at the solver's round-off prints as 0


def main() -> None:
    robot = hexaleg.load()
    prepared = hexaleg.prepare(robot, hexaleg.gait(robot, hexaleg.GaitParams(samples=200)))
    base = prepared.baseline()["total"]["joule"]
    print(f"default tripod gait, 200 samples: {base:.4f} J (Joule) per cycle without springs")
    for family in FAMILIES:
        result = hexaleg.design.studies.placement.placement(prepared, list(CLASSES), family)
        print(f"\n{family}: every set of sprung classes, best first")
        print(f"  {'springs':18s} {'energy':>8s} {'saving':>8s} {'old':>8s} {'gap':>7s}")
        for row in result.table.itertuples():
            print(f"  {row.springs:18s} {row.value:8.4f} {100 * row.saving:+7.2f}% "
                  f"{100 * row.old_saving:+7.2f}% {100 * row.gap:+6.2f}")
        best = result.optima[result.table["springs"].iloc[0]]
        print(f"  best set's springs ({best.family}, per class; rad from the centre of motion):")
        for g in best.groups:
            # an angle past which nothing acts prints —: any angle gives the same spring
            idle = hexaleg.design.families.family(best.family).idle(best.magnitudes[g], ROUND_OFF)
            geometry = ", ".join(f"{k} —" if k in idle else f"{k} {v:+.3f}"
                                 for k, v in best.geometry[g].items() if isinstance(v, float))
            values = ", ".join(f"{k} {v:.4g}" if abs(v) > ROUND_OFF else f"{k} 0"
                               for k, v in best.magnitudes[g].items())
            print(f"    {g:6s} {values}  [{geometry}]")


if __name__ == "__main__":
    main()
