"""Issue #56's 0.8× target simulated: the optimal cycle with the co-design's springs at another
stance length, predicted and walked in MuJoCo under both servos (logs:
analysis/bench_logs/bench_optimal_duty.log, before the stance hold, and
bench_optimal_duty_hold.log; not an example study: it needs the optimal extra and minutes).

Run:  python analysis/bench_optimal_duty.py --codesign DIR/codesign.json [--duty 0.9 ...]
                                            [--gait-only] [--nodes 40]
      python analysis/bench_optimal_duty.py --chosen cd.pkl ...   (G and S from the pickle
                                            analysis/bench_optimal_rows.py --chosen writes)

Needs the ``optimal`` extra. G is the search's best gait of a kept ``hexaleg codesign`` run (its
first finalist in ``codesign.json``: the gait of docs/optimal.md's 0.8× table), S its
inner-program springs (:func:`~hexaleg.design.codesign.gait_evaluation.evaluate_gait`, linear,
one design a joint class). Prints G with S predicted and simulated under each servo, then for each
duty factor G itself at that duty factor (with S, and with its own springs by the same program),
predicted and simulated under each servo, and (unless ``--gait-only``) the optimal cycle from G
at that duty factor with S in its dynamics (40 knots or ``--nodes``, 100 iterations), its
ratio to G's predicted J/m, its solver figures, and it — rebuilt in task space, as the
command's rows play it (:attr:`~hexaleg.optimal.solve.OptimalResult.task_space`) — predicted by
hexaleg's pipeline and simulated with S under each servo, open loop where the gait allows
(``feedback = "auto"``) and closed loop (``"on"``), as every row of G.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import os
import pickle
import time
from typing import Any

import hexaleg
from hexaleg.design.chain.groups import design_groups
from hexaleg.design.codesign.alternation import predicted_per_metre
from hexaleg.design.codesign.build import default_gait, floor_constraints
from hexaleg.design.codesign.gait_evaluation import evaluate_gait
from hexaleg.design.codesign.servo import simulated_run
from hexaleg.dynamics.prepare import prepare
from hexaleg.optimal.problem import OptimalParams, build_problem
from hexaleg.optimal.solve import solve

KEYS = ("period", "duty_factor", "step_height", "body_height", "foot_radius")
"""The gait's searched parameters read from ``codesign.json``."""


def predicted(robot: Any, motion: Any, motor: Any, springs: Any, contact: Any) -> str:
    """hexaleg's prediction of ``motion`` with ``springs`` (``predicted_per_metre``), as text:
    the J/m, or why there is none."""
    value, why = predicted_per_metre(robot, motion, motor, springs, contact)
    return f"{value:.3f} J/m" if value is not None else f"no prediction ({why})"


def sims(robot: Any, motion: Any, motor: Any, springs: Any, contact: Any) -> str:
    """``motion`` with ``springs`` simulated under both servos, open loop where the gait allows
    and closed loop: one line's text."""
    out = []
    for feedback in ("auto", "on"):
        for k in ("feedforward", "position"):
            value, why, closed = simulated_run(robot, motion, motor, springs, k, contact,
                                               feedback)
            loop = "balance feedback" if closed else "open loop"
            out.append(f"{k} {value:.3f} ({loop})" if value is not None else f"{k} — ({why})")
    return ", ".join(out)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    source = parser.add_mutually_exclusive_group(required=True)
    source.add_argument("--codesign", help="a hexaleg codesign run's JSON")
    source.add_argument("--chosen", help="a pickle of G and S (analysis/bench_optimal_rows.py)")
    parser.add_argument("--duty", type=float, nargs="+", default=[0.9], help="duty factors")
    parser.add_argument("--gait-only", action="store_true",
                        help="G at each duty factor only, no optimal cycle")
    parser.add_argument("--nodes", type=int, default=40, help="knots of the optimal cycle")
    args = parser.parse_args()
    t0 = time.perf_counter()
    run = hexaleg.Scenario.load("hexaleg")
    robot, motor = run.model, run.actuator
    c = floor_constraints(run)
    groups = design_groups(robot, tuple(robot.joint_classes), "class")
    if args.chosen:
        with open(args.chosen, "rb") as f:
            saved = pickle.load(f)
        g, springs, reference = saved["chosen"], saved["springs"], saved["per_metre"]
    else:
        with open(args.codesign, encoding="utf-8") as f:
            found = json.load(f)["finalists"]["rows"][0]["gait"]
        g = dataclasses.replace(default_gait(robot, "hexaleg", 0.06, None, 200),
                                **{k: found[k]["value"] for k in KEYS})
        point = evaluate_gait(robot, g, groups=groups, family="linear", constraints=c,
                              min_margin=0.0, motor=motor)
        springs, reference = point.springs, point.sprung / point.distance
    print(f"G: duty factor {g.duty_factor:.3g}, period {g.period:.4g} s: {reference:.4f} J/m "
          "with S (predicted)", flush=True)
    print("  G with S simulated: " + sims(robot, hexaleg.gait(robot, g), motor, springs,
                                         c.contact()), flush=True)
    for duty in args.duty:
        gd = dataclasses.replace(g, duty_factor=duty)
        played = hexaleg.gait(robot, gd)
        with_s = prepare(robot, played, motor=motor, contact=c.planning_contact()).evaluate(
            springs, "joule").metrics["total"]["electrical"] / gd.stride
        own = evaluate_gait(robot, gd, groups=groups, family="linear", constraints=c,
                            min_margin=0.0, motor=motor)
        for name, fitted, value in (("S", springs, with_s),
                                    ("its own springs", own.springs, own.sprung / own.distance)):
            print(f"G at duty factor {duty:.3g} with {name}: {value:.3f} J/m predicted, "
                  "simulated " + sims(robot, played, motor, fitted, c.contact()), flush=True)
        if args.gait_only:
            continue
        built = build_problem(robot, played, motor, springs, OptimalParams(nodes=args.nodes))
        r = solve(robot, built,
                  say=lambda line: print(f"  {line}", flush=True), every=20)
        print(f"optimal cycle at duty factor {duty:.3g} with S: {r.energy_per_metre:.4f} J/m = "
              f"{r.energy_per_metre / reference:.3f}× G predicted; stationarity "
              f"{r.stationarity:.2g} after {r.iterations} iterations, residual {r.residual:.1g} "
              f"N·m, friction use {r.friction_use:.3f}, stance slip {r.slip:.3g} m/s, "
              f"drift {r.drift:.2g} m, "
              f"periodicity {r.periodicity:.2g}, {r.seconds:.0f} s", flush=True)
        value, why = predicted_per_metre(robot, r.task_space, motor, springs, c.contact())
        said = (f"{value:.3f} J/m predicted ({value / reference:.3f}× G)" if value is not None
                else f"no prediction ({why})")
        print(f"  rebuilt in task space: {said}, "
              "simulated " + sims(robot, r.task_space, motor, springs, c.contact()), flush=True)
    times = os.times()
    print(f"wall {time.perf_counter() - t0:.0f} s, CPU {times.user + times.system:.0f} s",
          flush=True)


if __name__ == "__main__":
    main()
