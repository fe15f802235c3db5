"""The optimal motion's four rows, as ``hexaleg codesign --motion optimal`` computes them after its
search: the default robot at 0.06 m/s (log: analysis/bench_logs/bench_optimal_rows.log) or
Solo-12's trot at 0.3 m/s (``--robot solo12 --speed 0.3 --grouping mirrored``, log:
analysis/bench_logs/bench_optimal_rows_solo12.log); not an example study: it needs the optimal
extra and minutes.

Run:  python analysis/bench_optimal_rows.py [--robot hexaleg] [--speed 0.06] [--grouping class]
                                            [--max-evaluations 200] [--restarts 2]
                                            [--chosen cd.pkl] [--iterations 100]
                                            [--timing search]

Needs the ``optimal`` extra. The parametric co-design (``hexaleg.codesign``, no rules, no
simulation, no curve, the given grouping and search budget: its chosen gait and inner springs),
or both from the pickle ``--chosen`` names (written by this script, or by
``analysis/bench_optimal_target.py --chosen``: a re-run after a kill skips the search), then
:func:`hexaleg.design.codesign.optimal_rows.optimal_rows` (40 knots, the command's 100 iterations
or ``--iterations``, one alternation round on the co-design's spring groups) with each row
simulated under both servos; prints the rows as the command does, each optimal motion's solver
figures, the wall and CPU time; then the four rows' motions simulated again with balance
feedback on for every row (closed loop under both servos: apples to apples). ``--timing search``
searches the optimal motions' contact timing first (:mod:`hexaleg.design.codesign.timing`; log:
analysis/bench_logs/bench_optimal_rows_timing.log).
"""

from __future__ import annotations

import argparse
import os
import pickle
import time

import numpy as np
import pinocchio as pin

import hexaleg
from hexaleg.design.chain.groups import design_groups
from hexaleg.design.codesign.build import default_gait
from hexaleg.design.codesign.optimal_rows import optimal_rows
from hexaleg.design.codesign.servo import simulated_run
from hexaleg.motion.legged import gait
from hexaleg.optimal.problem import OptimalParams
from hexaleg.optimal.solve import OptimalResult
from hexaleg.robot.springs import SpringSet


def _rebuild_figures(result: OptimalResult) -> str:
    """How far the rebuilt cycle's base is from the solver's knots, how far it rolls about a
    two-foot support line, and how deep its swing feet go below the floor (the lowest stance
    foot of the cycle: level ground), at the knots and between them."""
    knots, rebuilt = result.motion, result.task_space
    per = rebuilt.info["per_knot"]
    offset = np.abs(rebuilt.q[::per, :3] - knots.q[:, :3]).max()
    turn = max(np.linalg.norm(pin.log3(pin.Quaternion(a[3:7]).toRotationMatrix().T
                                       @ pin.Quaternion(b[3:7]).toRotationMatrix()))
               for a, b in zip(rebuilt.q[::per], knots.q, strict=True))
    floor = rebuilt.feet[..., 2][rebuilt.stance].min()
    depth_knots = (floor - knots.feet[..., 2][~knots.stance]).max(initial=0.0)
    depth = (floor - rebuilt.feet[..., 2][~rebuilt.stance]).max(initial=0.0)
    roll = rebuilt.info["largest roll about a support line"]
    return (f"largest roll about a support line {1e3 * roll:.2f} mrad, "
            f"base within {1e3 * offset:.2f} mm and {1e3 * turn:.2f} mrad of its knots; swing "
            f"feet at most {1e3 * depth_knots:.3f} mm below the floor at the knots, "
            f"{1e3 * depth:.3f} mm between them")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--robot", default="hexaleg", help="registered robot")
    parser.add_argument("--speed", type=float, default=0.06, help="m/s")
    parser.add_argument("--grouping", default="class", help="class, mirrored or joint")
    parser.add_argument("--max-evaluations", type=int, default=200, help="search budget")
    parser.add_argument("--restarts", type=int, default=2, help="compass-search runs")
    parser.add_argument("--chosen", help="pickle of the co-design's chosen gait and springs "
                        "(read if it exists, else written after the search)")
    parser.add_argument("--iterations", type=int, default=100,
                        help="box-FDDP iterations of each solve (the command's: 100)")
    parser.add_argument("--timing", default="gait", help="gait or search (the contact timing)")
    args = parser.parse_args()
    t0, c0 = time.perf_counter(), os.times()
    run = hexaleg.Scenario.load(args.robot)
    robot = run.model
    if args.chosen and os.path.exists(args.chosen):
        with open(args.chosen, "rb") as f:
            saved = pickle.load(f)
        chosen, springs = saved["chosen"], saved["springs"]
        print(f"co-design from {args.chosen}", flush=True)
    else:
        para = hexaleg.codesign(args.robot, args.speed, rules=False, simulate=False,
                                curve=False, grouping=args.grouping,
                                max_evaluations=args.max_evaluations, restarts=args.restarts,
                                progress=lambda line: print(line, flush=True))
        chosen, springs, per_metre = para.chosen, para.springs, para.rows[3].per_metre
        rows = [(r.label, r.per_metre) for r in para.rows]
        print(f"co-design: {para.wall:.0f} s; rows "
              + " / ".join(f"{v:.4g}" for _, v in rows) + " J/m", flush=True)
        if args.chosen:
            with open(args.chosen + ".part", "wb") as f:
                pickle.dump({"chosen": chosen, "springs": springs, "per_metre": per_metre,
                             "rows": rows}, f)
            os.replace(args.chosen + ".part", args.chosen)  # whole or not at all
    print(f"chosen gait: duty factor {chosen.duty_factor:.4g}, period {chosen.period:.4g} s, "
          f"step height {chosen.step_height:.4g} m, body height {chosen.body_height:.4g} m",
          flush=True)
    base = default_gait(robot, args.robot, args.speed, None, chosen.samples)
    groups = design_groups(robot, tuple(robot.joint_classes), args.grouping)
    table = optimal_rows(robot, run.actuator, run.contact, base, chosen, springs,
                         groups=groups, rounds=1,
                         params=OptimalParams(iterations=args.iterations), timing=args.timing,
                         say=lambda line: print(line, flush=True))
    print("\n".join(table.lines()), flush=True)
    print("the same four motions, every simulation closed loop (balance feedback on: a position "
          "servo is asked for the plan's torque):", flush=True)
    played = (gait(robot, base), gait(robot, chosen), table.bare.task_space,
              table.alternation.motion)
    fitted = (SpringSet(), springs, SpringSet(), table.springs)
    for row, motion, s in zip(table.rows, played, fitted, strict=True):
        sims = []
        for k in row.simulated:
            value, verdict, _ = simulated_run(robot, motion, run.actuator, s, k, run.contact,
                                              "on")
            sims.append(f"{value:.2f}" if value is not None else f"— ({verdict})")
        predicted = f"{row.predicted:7.2f}" if row.predicted is not None else "      —"
        print(f"    {row.label:46s} {predicted}   {', '.join(sims)}", flush=True)
    for name, r in (("no springs", table.bare), ("its springs", table.best)):
        print(f"optimal motion, {name}: {r.iterations} iterations, stationarity "
              f"{r.stationarity:.2g} (threshold {r.threshold:.2g}), dynamics gap "
              f"{r.dynamic_gap:.2g}, residual {r.residual:.2g} N·m, friction use "
              f"{r.friction_use:.3f}, stance slip {r.slip:.3g} m/s, drift {r.drift:.2g} m, "
              f"periodicity {r.periodicity:.2g}, {r.seconds:.0f} s", flush=True)
    for name, r in (("no springs", table.bare), ("its springs", table.best)):
        print(f"optimal motion, {name}, rebuilt: {_rebuild_figures(r)}", flush=True)
    c1 = os.times()
    cpu = (c1.user - c0.user) + (c1.system - c0.system)
    print(f"wall {time.perf_counter() - t0:.0f} s, CPU {cpu:.0f} s", flush=True)


if __name__ == "__main__":
    main()
