"""Benchmark of the optimal motion and its springs on the default robot (issue #56: ≤ 10 min on
2 cores), with the numbers of docs/optimal.md's table.

Run:  python analysis/bench_optimal.py [--nodes 40] [--rounds 3] [--json out.json]
                                        [--from-codesign]

Needs the ``optimal`` extra (crocoddyl 3.2.1 with pin 4.0). In one process, as baselines: the
default gait's energy per metre by hexaleg's pipeline (RNEA and the force program, no springs)
and with the springs the project's design gives it (linear family, electrical metric). Then the
optimal cycle without springs, and the alternation of the optimal cycle and its springs
(:mod:`hexaleg.design.codesign.alternation`), each line of progress as it comes. Prints every
row's J/m — an optimal cycle's by hexaleg's prediction of the cycle rebuilt in task space
(:func:`~hexaleg.design.codesign.alternation.predicted_per_metre`, what the alternation judges
and the rows of ``codesign --motion optimal`` show), the solver's own figure at its knots
beside it — and its ratio to the default gait, the solver's figures (iterations, stationarity,
residual, friction use, stance slip), the wall time against the target and the CPU share (this
process's user + system CPU over the wall time: under 1 when other work shares the cores).
``--from-codesign`` also runs the parametric co-design (``hexaleg.codesign``, no rules, no
simulation, no curve) and the alternation from its chosen gait and springs: the issue's warm
start.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time

import hexaleg
from hexaleg.design.codesign.alternation import alternate, predicted_per_metre
from hexaleg.design.search.optimal import optimal_springs
from hexaleg.optimal.problem import OptimalParams, build_problem
from hexaleg.optimal.solve import solve

TARGET = 600.0
"""Issue #56's target wall time, s."""


def _say(line: str) -> None:
    print(f"  {line}", flush=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--nodes", type=int, default=40, help="knots per cycle")
    parser.add_argument("--rounds", type=int, default=3, help="alternation rounds at most")
    parser.add_argument("--json", help="write the rows to this JSON file")
    parser.add_argument("--from-codesign", action="store_true",
                        help="also start the alternation from the parametric co-design")
    args = parser.parse_args()
    start, cpu0 = time.perf_counter(), os.times()
    run = hexaleg.Scenario.load("hexaleg")
    robot, gait = run.model, run.motion()
    prepared = run.prepare()
    default = prepared.evaluate(hexaleg.SpringSet()).metrics["total"]["electrical"] / gait.distance
    sprung = optimal_springs(prepared, list(robot.joint_classes), family="linear",
                             metric="electrical")
    default_springs = sprung.analysis.metrics["total"]["electrical"] / gait.distance
    print(f"default gait: {default:.4g} J/m; with its linear springs {default_springs:.4g} J/m",
          flush=True)
    params = OptimalParams(nodes=args.nodes)
    print("optimal cycle without springs:", flush=True)
    bare = solve(robot, build_problem(robot, gait, run.actuator, hexaleg.SpringSet(), params),
                 say=_say)
    print("alternation (linear springs):", flush=True)
    alt = alternate(robot, gait, run.actuator, run.contact, springs=sprung.springs,
                    params=params, rounds=args.rounds, say=_say)
    if args.from_codesign:
        print("parametric co-design (no rules, no simulation):", flush=True)
        para = hexaleg.codesign(speed=gait.distance / gait.period, rules=False, simulate=False,
                                curve=False, progress=_say)
        best = min(para.rows, key=lambda r: r.per_metre)
        print(f"parametric co-design: {best.label} {best.per_metre:.4g} J/m", flush=True)
        chosen = hexaleg.gait(robot, para.chosen)
        print("alternation from the parametric co-design:", flush=True)
        alt_p = alternate(robot, chosen, run.actuator, run.contact, springs=para.springs,
                          params=params, rounds=args.rounds, say=_say)
    wall = time.perf_counter() - start
    cpu1 = os.times()
    cpu = (cpu1.user - cpu0.user) + (cpu1.system - cpu0.system)
    bare_predicted, why = predicted_per_metre(robot, bare.task_space, run.actuator,
                                              hexaleg.SpringSet(), run.contact)
    rows = {"default gait": default, "default gait, its linear springs": default_springs,
            "optimal cycle, no springs": bare_predicted or float("nan"),
            "optimal cycle, its springs (alternation)": alt.predicted or float("nan")}
    if args.from_codesign:
        rows["parametric co-design (its rows' best)"] = best.per_metre
        rows["optimal cycle from the co-design, its springs"] = alt_p.predicted or float("nan")
    print(f"\npredicted: an optimal cycle rebuilt in task space{' (' + why + ')' if why else ''}"
          f"; the solver's own J/m at its knots: {bare.energy_per_metre:.4g} (no springs), "
          f"{alt.best.energy_per_metre:.4g} (its springs)")
    print(f"\n{'row':44s} {'J/m':>8s} {'× default':>10s}")
    for name, value in rows.items():
        print(f"{name:44s} {value:8.4g} {value / default:10.3f}")
    results = [("no springs", bare), ("its springs", alt.best)]
    if args.from_codesign:
        results.append(("from the co-design, its springs", alt_p.best))
    for name, r in results:
        print(f"{name}: {r.iterations} iterations, stationarity {r.stationarity:.2g} "
              f"(threshold {r.threshold:.2g}), residual {r.residual:.2g} N·m, friction use "
              f"{r.friction_use:.3f}, slip {r.slip:.3g} m/s, drift {r.drift:.2g} m, "
              f"periodicity {r.periodicity:.2g}, "
              f"{r.seconds:.0f} s")
    print(f"alternation: {len(alt.rounds)} rounds, predicted (from the gait's) "
          f"{[None if e is None else round(e, 3) for e in alt.energies]}, last gain "
          f"{alt.gap:.3g}, the gait kept: {alt.kept_gait}; rounds "
          + "; ".join(f"springs {r.designed:.4g} on the cycle, solver {r.energy_per_metre:.4g}"
                      for r in alt.rounds))
    if args.from_codesign:
        print(f"alternation from the co-design: {len(alt_p.rounds)} rounds, predicted "
              f"{alt_p.energies}, last gain {alt_p.gap:.3g}, the gait kept: {alt_p.kept_gait}")
    print(f"wall {wall:.0f} s = {wall / TARGET:.2f} × the {TARGET:.0f} s target; CPU share "
          f"{cpu / wall:.2f}")
    if args.json:
        with open(args.json, "w", encoding="utf-8") as f:
            json.dump({"rows": rows, "energies": alt.energies, "wall": wall, "cpu": cpu,
                       "nodes": args.nodes, "residual": alt.best.residual,
                       "friction_use": alt.best.friction_use, "slip": alt.best.slip,
                       "springs": repr(alt.springs)}, f, indent=1)
    sys.stdout.flush()


if __name__ == "__main__":
    main()
