"""What bounds the optimal motion's gain (issue #56's 0.8× target): the energy of the co-design's
gait G with its springs S and of the optimal motion with its springs, split per joint class into
the motors' Joule loss and their mechanical part, and what springs could still remove on the
optimal motion (log: analysis/bench_logs/bench_optimal_breakdown.log; not an example study: it
needs the optimal extra and minutes).

Run:  python analysis/bench_optimal_breakdown.py --chosen cd.pkl [--duty 0.8] [--period 1.0]
                                                 [--families linear dead_zone stiffening]

Needs the ``optimal`` extra. G and S from the pickle analysis/bench_optimal_rows.py ``--chosen``
writes. The optimal motion: the cycle from G at duty factor ``--duty`` and period ``--period`` ×
G's, with S in its dynamics (40 knots, 100 iterations), then one round of the alternation
(:func:`hexaleg.design.codesign.alternation.alternate`, the rows' answer), played rebuilt in task
space. Each motion is analysed by hexaleg's pipeline (the force program, objective ``joule``, as
the rows predict): per joint class, the electrical energy per metre (no regeneration), its Joule
part ``c u²`` and the rest (the mechanical power through η, ``max(P/η, ηP)``), and the positive
mechanical work of the motors. Then, on the optimal motion, the springs the project's global
convex design gives with more freedom than the rows' (one design a joint instead of a joint
class; the linear family, or those ``--families`` names — a nonlinear family's design takes
many minutes on a shared machine): how much of the remaining energy any of them removes.
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import pickle
import time
from typing import Any

import numpy as np

import hexaleg
from hexaleg.design.chain.groups import design_groups
from hexaleg.design.codesign.alternation import alternate
from hexaleg.design.search.optimal import optimal_springs
from hexaleg.dynamics.prepare import prepare
from hexaleg.optimal.problem import OptimalParams, build_problem
from hexaleg.optimal.solve import solve


def breakdown(name: str, robot: Any, motion: Any, motor: Any, springs: Any, contact: Any) -> None:
    """Print ``motion`` with ``springs`` split per joint class (module docstring)."""
    m = prepare(robot, motion, motor=motor, contact=contact).evaluate(springs, "joule").metrics
    names = list(m["joint_names"])
    d = motion.distance
    total = m["total"]["electrical"] / d
    print(f"{name}: {total:.3f} J/m electrical, of which Joule {m['total']['joule'] / d:.3f} "
          f"({m['total']['joule'] / m['total']['electrical']:.0%}), mechanical through η "
          f"{(m['total']['electrical'] - m['total']['joule']) / d:.3f}; motors' positive work "
          f"{m['total']['positive_work'] / d:.3f} J/m", flush=True)
    for cls, joints in robot.joint_classes.items():
        rows = [names.index(j) for j in joints]
        e, j_, w = (float(np.sum(np.asarray(m["joint"][k])[rows])) / d
                    for k in ("electrical", "joule", "positive_work"))
        print(f"  {cls:6s} electrical {e:6.3f} J/m ({e / total:4.0%}): Joule {j_:6.3f}, "
              f"mechanical {e - j_:6.3f}; positive work {w:6.3f}", flush=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--chosen", required=True, help="pickle of G and S")
    parser.add_argument("--duty", type=float, help="the optimal cycle's duty factor (G's)")
    parser.add_argument("--period", type=float, default=1.0, help="its period, × G's")
    parser.add_argument("--families", nargs="+", default=["linear"], help="spring families")
    args = parser.parse_args()
    t0 = time.perf_counter()
    with open(args.chosen, "rb") as f:
        saved = pickle.load(f)
    g, s = saved["chosen"], saved["springs"]
    run = hexaleg.Scenario.load("hexaleg")
    robot, motor, contact = run.model, run.actuator, run.contact
    breakdown("G with S", robot, hexaleg.gait(robot, g), motor, s, contact)
    timed = dataclasses.replace(g, duty_factor=args.duty or g.duty_factor,
                                period=g.period * args.period)
    motion = hexaleg.gait(robot, timed)
    params = OptimalParams()
    first = solve(robot, build_problem(robot, motion, motor, s, params))
    alt = alternate(robot, motion, motor, contact, springs=s, params=params, rounds=1,
                    first=first, say=lambda line: print(f"  {line}", flush=True))
    print(f"optimal motion at duty factor {timed.duty_factor:.3g}, period {timed.period:.4g} s: "
          f"alternation {alt.energies} J/m predicted (the gait kept: {alt.kept_gait})",
          flush=True)
    played = alt.motion
    breakdown("the optimal motion with its springs", robot, played, motor, alt.springs, contact)
    breakdown("the optimal motion without springs", robot, played, motor, hexaleg.SpringSet(),
              contact)
    prepared = prepare(robot, played, motor=motor, contact=contact)
    for grouping in ("class", "joint"):
        groups = design_groups(robot, tuple(robot.joint_classes), grouping)
        for family in args.families:
            design = optimal_springs(prepared, groups, family=family, metric="electrical")
            value = design.analysis.metrics["total"]["electrical"] / played.distance
            print(f"  on the optimal motion, {family} springs one design a {grouping}: "
                  f"{value:.3f} J/m", flush=True)
    times = os.times()
    print(f"wall {time.perf_counter() - t0:.0f} s, CPU {times.user + times.system:.0f} s",
          flush=True)


if __name__ == "__main__":
    main()
