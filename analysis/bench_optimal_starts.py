"""The optimal motion's multi-start (issue #56's 0.8× target): from the co-design's gait G and
springs S at a contact timing, the fixed lattice of starts of
:mod:`hexaleg.design.codesign.starts` (step height, body height, swing weight), each judged by
hexaleg's prediction of its rebuilt cycle, the alternation from the best, and the answer
predicted and simulated under both servos with balance feedback on, against the parametric
co-design searched to the same duty-factor bound, in the same process (log:
analysis/bench_logs/bench_optimal_starts.log; not an example study: it needs the optimal extra
and many minutes).

Run:  python analysis/bench_optimal_starts.py --chosen cd.pkl --duty 0.85
                                             --baseline cd09.pkl [--period 1.0]

Needs the ``optimal`` extra. G and S from the pickle ``--chosen`` (written by
analysis/bench_optimal_rows.py or analysis/bench_codesign_duty_bound.py ``--chosen``); the
timing: G's duty factor ``--duty`` (the timing search's choice: 0.85) and period ``--period`` ×
G's. The baseline: the parametric co-design's gait and springs from ``--baseline`` (the
co-design searched to the timing lattice's bound, 0.9: analysis/bench_codesign_duty_bound.py),
predicted and simulated here. Each motion (the timed gait with S, the answer with its springs,
the baseline) is then split per joint class into the motors' Joule heat and the rest (the
mechanical power through η), with the motors' positive work: what a motion change can still
touch.
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import pickle
import time
from typing import Any

from bench_optimal_breakdown import breakdown  # the per-joint-class split, printed alike

import hexaleg
from hexaleg.design.codesign.alternation import alternate, predicted_per_metre
from hexaleg.design.codesign.gait_evaluation import Constraints
from hexaleg.design.codesign.servo import simulated_run
from hexaleg.design.codesign.starts import search_starts
from hexaleg.optimal.problem import OptimalParams


def simulated(robot: Any, motion: Any, motor: Any, springs: Any, contact: Any) -> dict[str, Any]:
    """Simulated J/m under each servo, balance feedback on (None: it did not walk)."""
    out = {}
    for k in ("feedforward", "position"):
        out[k], _, _ = simulated_run(robot, motion, motor, springs, k, contact, "on")
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--chosen", required=True, help="pickle of G and S")
    parser.add_argument("--baseline", required=True, help="pickle of the co-design at the bound")
    parser.add_argument("--duty", type=float, help="the timing's duty factor (G's)")
    parser.add_argument("--period", type=float, default=1.0, help="its period, × G's")
    args = parser.parse_args()
    t0 = time.perf_counter()
    with open(args.chosen, "rb") as f:
        saved = pickle.load(f)
    with open(args.baseline, "rb") as f:
        base = pickle.load(f)
    g, s = saved["chosen"], saved["springs"]
    run = hexaleg.Scenario.load("hexaleg")
    robot, motor, contact = run.model, run.actuator, run.contact
    b_motion = hexaleg.gait(robot, base["chosen"])
    b_pred, _ = predicted_per_metre(robot, b_motion, motor, base["springs"], contact)
    b_sims = simulated(robot, b_motion, motor, base["springs"], contact)
    print(f"baseline: the co-design at duty factor ≤ 0.9 (duty {base['chosen'].duty_factor:.4g},"
          f" period {base['chosen'].period:.4g} s): {b_pred:.3f} J/m predicted, simulated with "
          f"balance feedback " + ", ".join(f"{k} {v:.2f}" for k, v in b_sims.items()),
          flush=True)
    timed = dataclasses.replace(g, duty_factor=args.duty or g.duty_factor,
                                period=g.period * args.period)
    params = OptimalParams()
    found = search_starts(robot, timed, motor, s, contact, params,
                          Constraints().min_foot_clearance,
                          say=lambda line: print(f"  {line}", flush=True))
    print(found.line(), flush=True)
    best = found.chosen
    alt = alternate(robot, hexaleg.gait(robot, best.params), motor, contact, springs=s,
                    params=best.settings, first=best.result,
                    say=lambda line: print(f"  alternation: {line}", flush=True))
    value = alt.predicted
    sims = simulated(robot, alt.motion, motor, alt.springs, contact)
    print(f"the answer (start: {best.label}): alternation "
          + " → ".join("—" if e is None else f"{e:.3f}" for e in alt.energies)
          + f" J/m predicted (the gait kept: {alt.kept_gait}); simulated with balance feedback "
          + ", ".join(f"{k} {v:.2f}" if v is not None else f"{k} —" for k, v in sims.items()),
          flush=True)
    r = alt.best
    print(f"its solve: residual {r.residual:.1g} N·m, stationarity {r.stationarity:.2g} after "
          f"{r.iterations} iterations, friction use {r.friction_use:.2f}, slip {r.slip:.3g} m/s,"
          f" drift {r.drift:.3g} m, periodicity gap {r.periodicity:.2g}", flush=True)
    if value is not None and b_pred:
        worse = max((v for v in sims.values() if v is not None), default=float("nan"))
        b_worse = max(v for v in b_sims.values() if v is not None)
        print(f"against the co-design at the same duty bound: predicted {value / b_pred:.3f}× "
              f"(target ≤ 0.8), simulated under the worse servo {worse / b_worse:.3f}× "
              f"(target ≤ 0.85)", flush=True)
    breakdown("the timed gait with S", robot, hexaleg.gait(robot, timed), motor, s, contact)
    breakdown("the answer with its springs", robot, alt.motion, motor, alt.springs, contact)
    breakdown("the answer without springs", robot, alt.motion, motor, hexaleg.SpringSet(), contact)
    breakdown("the co-design at the bound with its springs", robot, b_motion, motor,
          base["springs"], contact)
    times = os.times()
    print(f"wall {time.perf_counter() - t0:.0f} s, CPU {times.user + times.system:.0f} s",
          flush=True)


if __name__ == "__main__":
    main()
