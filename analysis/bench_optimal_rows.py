"""The optimal motion's four rows on the default robot at 0.06 m/s, as ``hexaleg codesign --motion
optimal`` computes them after its search (log: analysis/bench_logs/bench_optimal_rows.log;
not an example study: it needs the optimal extra and ten minutes).

Run:  python analysis/bench_optimal_rows.py [--chosen cd.pkl]

Needs the ``optimal`` extra. The parametric co-design (``hexaleg.codesign``, no rules, no
simulation, no curve: its chosen gait and inner springs; or both from the pickle of
``analysis/bench_optimal_target.py --chosen``), then
:func:`hexaleg.design.codesign.optimal_rows.optimal_rows` (40 knots, 100 iterations, one
alternation round) with each row simulated under both servos; prints the rows as the command
does, the wall and CPU time.
"""

from __future__ import annotations

import argparse
import os
import pickle
import time

import hexaleg
from hexaleg.design.codesign.build import default_gait
from hexaleg.design.codesign.optimal_rows import optimal_rows


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--chosen", help="pickle of the co-design's chosen gait and springs")
    args = parser.parse_args()
    t0, c0 = time.perf_counter(), os.times()
    run = hexaleg.Scenario.load("hexaleg")
    robot = run.model
    if args.chosen and os.path.exists(args.chosen):
        with open(args.chosen, "rb") as f:
            saved = pickle.load(f)
        chosen, springs, per_metre = saved["chosen"], saved["springs"], saved["per_metre"]
        default = dict(saved["rows"])["default gait, no springs"]
    else:
        para = hexaleg.codesign(speed=0.06, rules=False, simulate=False, curve=False)
        chosen, springs, per_metre = para.chosen, para.springs, para.rows[3].per_metre
        default = para.rows[0].per_metre
    base = default_gait(robot, "hexaleg", 0.06, None, chosen.samples)
    table = optimal_rows(robot, run.actuator, run.contact, base, chosen, springs,
                         (default, per_metre), rounds=1,
                         say=lambda line: print(line, flush=True))
    print("\n".join(table.lines()), flush=True)
    c1 = os.times()
    cpu = (c1.user - c0.user) + (c1.system - c0.system)
    print(f"wall {time.perf_counter() - t0:.0f} s, CPU {cpu:.0f} s", flush=True)


if __name__ == "__main__":
    main()
