"""The globally optimal springs per joint class and family on hexaleg's default tripod gait, and
how far the old grid + Nelder–Mead search was from them.

Run:  python analysis/design_hexaleg.py   (expected output: analysis/logs/design_hexaleg.log)

The default gait at 200 samples per cycle, AX-18A servos, minimum-Joule foot forces, μ = 0.6.
Per joint class (the same spring on all six legs):

* "Nelder–Mead": today's :func:`optimise` on the Joule energy — a symmetric dead zone
  (k, θ_k) with its neutral offset free in ±1 rad, grid start then Nelder–Mead;
* "same geometry": :func:`hexaleg.optimal_springs` with the dead-zone family at exactly the
  Nelder–Mead geometry (θ⁻ = offset − θ_k, θ⁺ = offset + θ_k), k⁺ and k⁻ from the convex
  program — never worse (the magnitudes are globally optimal for that geometry);
* each family with its geometry searched (the linear family has none: its answer is global).

Energies are the Joule energy per cycle (J); savings against the same gait without springs.
Angles are from the centre of each joint's range of motion in the gait; an angle past which
nothing acts (its stiffness and preload 0) prints "—": any angle gives the same spring.
"""

from __future__ import annotations

import hexaleg
from hexaleg.design.evaluator import Evaluator
from hexaleg.design.families import FAMILIES, family
from hexaleg.design.search.optimal import OptimalSprings
from hexaleg.design.studies.optimise import optimise

CLASSES = ("coxa", "femur", "tibia")
ROUND_OFF = 1e-6
"""N·m/rad or N·m: a magnitude at the solver's round-off prints as 0 (the interior point stops at
~1e-8 of the largest, and those digits change with the BLAS kernels); real ones are ~1e-2."""


def _magnitudes(res: OptimalSprings, group: str) -> str:
    # an angle past which nothing acts prints —: the search left it anywhere, and any angle gives
    # the same spring (Family.idle, with the magnitudes' own zero)
    idle = family(res.family).idle(res.magnitudes[group], ROUND_OFF)
    geometry = ", ".join(f"{k} —" if k in idle else f"{k} {v:+.3f}" if isinstance(v, float)
                         else f"{k} {v}" for k, v in res.geometry[group].items())
    values = ", ".join(f"{k} {v:.4g}" if abs(v) > ROUND_OFF else f"{k} 0"
                       for k, v in res.magnitudes[group].items())
    return f"{values}" + (f"  [{geometry}]" if geometry else "")


def main() -> None:
    robot = hexaleg.load()
    motion = hexaleg.gait(robot, hexaleg.GaitParams(samples=200))
    prepared = hexaleg.prepare(robot, motion)
    ev = Evaluator(prepared)
    base = prepared.baseline()["total"]["joule"]
    print(f"default tripod gait, 200 samples, joule per cycle without springs {base:.4f} J")
    for cls in CLASSES:
        print(f"\n{cls}")
        old = optimise(ev, cls, robot.joints(cls), "joule", offset_bounds=(-1.0, 1.0))
        print(f"  {'Nelder–Mead (dead zone)':<26} {old.value:.4f} J  saving "
              f"{100 * old.saving:+6.2f} %  k {old.k:.4g}, theta_k {old.theta_k:.3f}, "
              f"offset {old.offset:+.3f}")
        same = hexaleg.optimal_springs(prepared, [cls], "dead_zone", geometry={cls: {
            "theta_minus": old.offset - old.theta_k, "theta_plus": old.offset + old.theta_k}})
        # ≥ 0 (the convex optimum is global at that geometry); a rounding-level negative
        # would print "-0.00" on one machine and "0.00" on another: round, then drop the sign
        # of zero (a real negative still prints)
        gap = round(100 * (old.value - same.value) / old.value, 2) + 0.0
        print(f"  {'same geometry, convex':<26} {same.value:.4f} J  saving "
              f"{100 * same.saving:+6.2f} %  {_magnitudes(same, cls)}  "
              f"(Nelder–Mead {gap:.2f} % above)")
        for fam in FAMILIES:
            res = hexaleg.optimal_springs(prepared, [cls], fam)
            print(f"  {fam + ', searched':<26} {res.value:.4f} J  saving "
                  f"{100 * res.saving:+6.2f} %  {_magnitudes(res, cls)}")


if __name__ == "__main__":
    main()
