"""The parametric co-design's baseline at a widened duty-factor bound (issue #56's caveat on the
contact timing): the default robot at 0.06 m/s searched with the duty factor up to 0.9 instead of
0.8, its chosen gait and springs predicted and simulated under both servos with balance feedback
on (log: analysis/bench_logs/bench_codesign_duty_bound.log; not an example study: minutes).

Run:  python analysis/bench_codesign_duty_bound.py [--duty-high 0.9] [--body-high 1.3]
                                                  [--chosen out.pkl]

The co-design's search box (:func:`hexaleg.design.codesign.box.default_space`) bounds
the duty factor at 0.8 by default (``[codesign] duty_high``, ``--duty-high``); the optimal
motion's timing search (``codesign --motion optimal``) may reach 0.9, so the parametric family at
the same bound is the fair baseline. Runs ``hexaleg.codesign`` (no rules, no simulated
finalists, no curve: the search's best gait and its inner springs, as
analysis/bench_optimal_rows.py's ``cd.pkl``) with ``duty_high`` raised, then the
chosen gait with its springs simulated under each servo, closed loop. ``--chosen`` writes the
gait and springs as a pickle that analysis/bench_optimal_rows.py and bench_optimal_duty.py read.

``--body-high F`` widens the search box's body height from 1.3 × the default gait's to F × it
(``[codesign] body_high``, ``--body-high``): the optimal motion's multi-start chose a body
height above 1.3 × (docs/optimal.md, "Starts of the optimal motion"), so the parametric family
with that box widened is the fair baseline there (log:
analysis/bench_logs/bench_codesign_body_bound.log).
"""

from __future__ import annotations

import argparse
import os
import pickle
import time

import hexaleg
from hexaleg.design.codesign.servo import simulated_run


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duty-high", type=float, default=0.9, help="the duty factor's bound")
    parser.add_argument("--body-high", type=float, default=1.3,
                        help="the body height's top, × the default gait's")
    parser.add_argument("--chosen", help="write the chosen gait and springs to this pickle")
    args = parser.parse_args()
    t0 = time.perf_counter()
    para = hexaleg.codesign("hexaleg", 0.06, rules=False, simulate=False, curve=False,
                            duty_high=args.duty_high, body_high=args.body_high,
                            progress=lambda line: print(line, flush=True))
    chosen, springs = para.chosen, para.springs
    rows = [(r.label, r.per_metre) for r in para.rows]
    print(f"duty-factor bound {args.duty_high}: rows " + " / ".join(f"{v:.4g}" for _, v in rows)
          + " J/m", flush=True)
    print(f"chosen gait: duty factor {chosen.duty_factor:.4g}, period {chosen.period:.4g} s, "
          f"step height {chosen.step_height:.4g} m, body height {chosen.body_height:.4g} m "
          f"(box top {para.body_high * para.default.body_height:.4g} m)", flush=True)
    if args.chosen:
        with open(args.chosen + ".part", "wb") as f:
            pickle.dump({"chosen": chosen, "springs": springs, "per_metre": rows[3][1],
                         "rows": rows}, f)
        os.replace(args.chosen + ".part", args.chosen)
    run = hexaleg.Scenario.load("hexaleg")
    motion = hexaleg.gait(run.model, chosen)
    sims = []
    for k in ("feedforward", "position"):
        value, verdict, _ = simulated_run(run.model, motion, run.actuator, springs, k,
                                          run.contact, "on")
        sims.append(f"{k} {value:.2f}" if value is not None else f"{k} — ({verdict})")
    body = "" if args.body_high == 1.3 else f", body height ≤ {args.body_high} × the default"
    print(f"co-design at duty-factor bound {args.duty_high}{body}: {rows[3][1]:.2f} J/m predicted, "
          f"simulated with balance feedback: {', '.join(sims)}", flush=True)
    times = os.times()
    print(f"wall {time.perf_counter() - t0:.0f} s, CPU {times.user + times.system:.0f} s",
          flush=True)


if __name__ == "__main__":
    main()
