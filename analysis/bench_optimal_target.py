"""Issue #56's 0.8× target: what moves the optimal motion with its springs below the parametric
co-design's J/m on the default robot at 0.06 m/s (log:
analysis/bench_logs/bench_optimal_target.log).

Run:  python analysis/bench_optimal_target.py [--chosen cd.pkl] [--json out.json]

Needs the ``optimal`` extra. The parametric co-design (``hexaleg.codesign``, no rules, no
simulation, no curve; or its chosen gait and springs from a pickle ``--chosen`` wrote by an
earlier run) gives the gait G and springs S. Every experiment solves the optimal cycle with S in
the dynamics from a gait, 40 knots, and prints its exact J/m and its ratio to the co-design's
(predicted, both):

1. ``base``: from G, 100 iterations (docs/optimal.md's 9.14 J/m);
2. ``iterations``: the base cycle continued for 200 more iterations (its states and controls the
   warm start);
3. ``timing``: from G with its period × 1.15 and × 0.85, its duty factor − 0.05, + 0.05, + 0.10
   (the contact timing as a decision of an outer search; the stride follows ``speed × period``);
4. ``proximal``: the base cycle re-solved, re-centred on itself (its states the regularisation's
   reference and warm start, its feet the swing path) with the state weight 1e-4 — a
   proximal-point step of the regularisation schedule;
5. ``starts``: from G with its step height × 0.7 and × 1.3 (other starts of the same timing).

In that order (the likeliest gains first: on the shared 2-core machine one solve took 1 to 6
minutes).
Then the alternation (:func:`hexaleg.design.codesign.alternation.alternate`) from the best gait
found, each round's energy printed. Each line is printed as it comes; ``--json`` is rewritten
after each experiment (a killed run keeps what it finished).
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
from hexaleg.design.codesign.alternation import alternate
from hexaleg.optimal.problem import OptimalParams, build_problem
from hexaleg.optimal.solve import solve


def _say(line: str) -> None:
    print(f"  {line}", flush=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--chosen", help="pickle of the co-design's chosen gait and springs")
    parser.add_argument("--json", help="write the experiments to this JSON file as they end")
    args = parser.parse_args()
    start, cpu0 = time.perf_counter(), os.times()
    run = hexaleg.Scenario.load("hexaleg")
    robot, motor = run.model, run.actuator
    if args.chosen and os.path.exists(args.chosen):
        with open(args.chosen, "rb") as f:
            saved = pickle.load(f)
        chosen, springs, reference = saved["chosen"], saved["springs"], saved["per_metre"]
    else:
        para = hexaleg.codesign(speed=0.06, rules=False, simulate=False, curve=False)
        chosen, springs = para.chosen, para.springs
        reference = para.rows[3].per_metre
        if args.chosen:
            with open(args.chosen, "wb") as f:
                pickle.dump({"chosen": chosen, "springs": springs, "per_metre": reference,
                             "rows": [(r.label, r.per_metre) for r in para.rows]}, f)
    print(f"parametric co-design: {reference:.4g} J/m; duty factor {chosen.duty_factor:.4g}, "
          f"period {chosen.period:.4g} s, step height {chosen.step_height:.4g} m, body height "
          f"{chosen.body_height:.4g} m", flush=True)
    out: dict[str, Any] = {"reference": reference, "experiments": {}}

    def record(name: str, r: Any, note: str = "") -> None:
        print(f"{name:28s} {r.energy_per_metre:8.4f} J/m  {r.energy_per_metre / reference:6.3f}×"
              f"  stationarity {r.stationarity:.2g} after {r.iterations}, friction use "
              f"{r.friction_use:.3f}, residual {r.residual:.1g} N·m, {r.seconds:.0f} s {note}",
              flush=True)
        out["experiments"][name] = {"per_metre": r.energy_per_metre,
                                    "ratio": r.energy_per_metre / reference,
                                    "stationarity": r.stationarity, "iterations": r.iterations,
                                    "friction_use": r.friction_use, "residual": r.residual,
                                    "seconds": r.seconds}
        if args.json:
            with open(args.json, "w", encoding="utf-8") as f:
                json.dump(out, f, indent=1)

    def cycle(params_g: Any, params: OptimalParams | None = None, motion: Any = None) -> Any:
        played = motion if motion is not None else hexaleg.gait(robot, params_g)
        return solve(robot, build_problem(robot, played, motor, springs, params))

    g = hexaleg.gait(robot, chosen)
    results: dict[str, tuple[Any, Any]] = {}
    base = cycle(chosen, motion=g)
    record("base (100 iterations)", base)
    results["base"] = (chosen, base)
    more = solve(robot, build_problem(robot, g, motor, springs, OptimalParams(iterations=200)),
                 warm=(base.x, base.torques))
    record("continued, 300 iterations", more)
    variants = {
        "period × 1.15": {"period": 1.15 * chosen.period},
        "period × 0.85": {"period": 0.85 * chosen.period},
        "duty factor − 0.05": {"duty_factor": chosen.duty_factor - 0.05},
        "duty factor + 0.05": {"duty_factor": chosen.duty_factor + 0.05},
        "duty factor + 0.10": {"duty_factor": chosen.duty_factor + 0.10},
        "proximal": None,
        "step height × 0.7": {"step_height": 0.7 * chosen.step_height},
        "step height × 1.3": {"step_height": 1.3 * chosen.step_height},
    }
    for name, change in variants.items():
        if change is None:
            record("proximal, state weight 1e-4",
                   cycle(None, OptimalParams(state_weight=1e-4), motion=base.motion))
            continue
        params_g = dataclasses.replace(chosen, **change)
        try:
            r = cycle(params_g)
        except hexaleg.HexalegError as err:
            print(f"{name:28s} failed: {err}", flush=True)
            continue
        record(name, r)
        results[name] = (params_g, r)
    best_name = min(results, key=lambda k: results[k][1].energy_per_metre)
    best_gait = results[best_name][0]
    print(f"alternation from the best start ({best_name}):", flush=True)
    alt = alternate(robot, hexaleg.gait(robot, best_gait), motor, run.contact, springs=springs,
                    rounds=3, say=_say)
    record(f"alternation from {best_name}", alt.best,
           f"energies {[round(e, 4) for e in alt.energies]}")
    wall = time.perf_counter() - start
    cpu1 = os.times()
    cpu = (cpu1.user - cpu0.user) + (cpu1.system - cpu0.system)
    print(f"wall {wall:.0f} s, CPU share {cpu / wall:.2f}", flush=True)


if __name__ == "__main__":
    main()
