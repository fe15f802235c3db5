"""Where two optimal solves from starts 1e-9 apart part, and the spread the rows state (issue
#56's same answer): from the co-design's gait G and springs S (the optimal motion's start of
``hexaleg codesign --motion optimal``), the box-FDDP solve of G with S in its dynamics run twice,
the second with G's body height moved by 1e-9 m (its start's knots then move by up to 3e-8), each
iterate recorded; prints the two solves' cost, line-search step and regularisation iteration by
iteration with the largest difference of their knots' states and controls, where they part and
how fast, then each solve's judged figure (hexaleg's prediction of its cycle rebuilt in task
space with S: :func:`~hexaleg.design.codesign.alternation.judged`), its solver figure and
stationarity; then that solve's spread as the rows measure it
(:func:`~hexaleg.design.codesign.alternation.spreads`: the solve again from its start moved by
±1e-9 and ±2e-9 m in the base's height; the rows repeat the whole alternation this way). Log:
analysis/bench_logs/bench_optimal_same_answer.log, at 100 iterations then at 300 (not an example
study: it needs the optimal extra and a minute or two).

Run:  python analysis/bench_optimal_same_answer.py --chosen cd.pkl [--body 1.0] [--duty D]
                                                   [--iterations 100]

``--chosen``: the pickle of ``analysis/bench_optimal_rows.py --chosen`` (the parametric
co-design's chosen gait and inner springs); ``--body`` scales G's body height (1.3: the probe of
docs/optimal.md's "What is left", with ``--duty 0.85``).
"""

from __future__ import annotations

import argparse
import dataclasses
import pickle
import time
from typing import Any

import numpy as np

import hexaleg
from hexaleg.design.codesign.alternation import judged, spreads
from hexaleg.optimal.problem import OptimalParams, build_problem
from hexaleg.optimal.solve import crocoddyl, solve

MOVE = 1e-9
"""The body height's move, m (the same-answer rule's)."""


class Recorder(crocoddyl.CallbackAbstract):  # type: ignore[misc]
    """Each iterate's cost, stopping criterion, step, regularisation, states and controls."""

    def __init__(self) -> None:
        crocoddyl.CallbackAbstract.__init__(self)
        self.log: list[dict[str, Any]] = []

    def __call__(self, solver: Any) -> None:
        self.log.append({"cost": solver.cost, "stop": solver.stop, "step": solver.stepLength,
                         "reg": solver.preg, "xs": np.array(solver.xs),
                         "us": np.array(solver.us)})


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--chosen", required=True)
    parser.add_argument("--body", type=float, default=1.0)
    parser.add_argument("--duty", type=float, default=None)
    parser.add_argument("--iterations", type=int, default=100)
    args = parser.parse_args()
    began, cpu = time.perf_counter(), time.process_time()
    with open(args.chosen, "rb") as f:
        saved = pickle.load(f)
    chosen, springs = saved["chosen"], saved["springs"]
    run = hexaleg.Scenario.load("hexaleg")
    robot, motor, contact = run.model, run.actuator, run.contact
    timed = dataclasses.replace(chosen, body_height=chosen.body_height * args.body,
                                duty_factor=args.duty or chosen.duty_factor)
    params = OptimalParams(iterations=args.iterations)
    print(f"G: duty factor {timed.duty_factor:.4g}, period {timed.period:.6g} s, step height "
          f"{timed.step_height:.4g} m, body height {timed.body_height!r} m; S: "
          f"{', '.join(springs) or 'none'}; {params.nodes} knots, {params.iterations} "
          "iterations", flush=True)
    logs, starts, results, gaits = [], [], [], []
    for move in (0.0, MOVE):
        gait = hexaleg.gait(robot, dataclasses.replace(
            timed, body_height=timed.body_height + move))
        built = build_problem(robot, gait, motor, springs, params)
        solver = crocoddyl.SolverBoxFDDP(built.problem)
        solver.th_stop = params.stop
        recorder = Recorder()
        solver.setCallbacks([recorder])
        xs = [np.array(x) for x in built.x_warm]
        us = list(built.problem.quasiStatic(xs[:-1]))
        starts.append((np.array(xs), np.array(us)))
        solver.solve(xs, us, params.iterations, False)
        result = solve(robot, built)  # the command's solve: the same iterates
        assert np.array_equal(result.x, np.array(solver.xs))
        logs.append(recorder.log)
        results.append(result)
        gaits.append(gait)
    (xa, ua), (xb, ub) = starts
    print(f"the starts differ by {np.abs(xa - xb).max():.2g} in the states, "
          f"{np.abs(ua - ub).max():.2g} N·m in the controls")
    print("iteration  cost (G)  cost (moved)  step (G)  step (moved)  reg  |Δx|∞  |Δu|∞ N·m  "
          "stop (G)")
    apart = []
    for k, (a, b) in enumerate(zip(*logs, strict=True)):
        dx = float(np.abs(a["xs"] - b["xs"]).max())
        apart.append(dx)
        if k % 3 == 0 or k == len(logs[0]) - 1:
            print(f"{k:9d}  {a['cost']:.8f}  {b['cost']:.8f}  {a['step']:.4g}  {b['step']:.4g}  "
                  f"{a['reg']:.2g}  {dx:.2e}  {float(np.abs(a['us'] - b['us']).max()):.2e}  "
                  f"{a['stop']:.3g}")
    first = next((k for k, d in enumerate(apart) if d > 1e-6), None)
    wide = next((k for k, d in enumerate(apart) if d > 1e-4), None)
    if first is not None and wide is not None and wide > first:
        rate = (apart[wide] / apart[first]) ** (1.0 / (wide - first))
        print(f"they part at iteration {first} (|Δx|∞ {apart[first]:.2g}) and reach "
              f"{apart[wide]:.2g} at iteration {wide}: × {rate:.2f} an iteration")
    for label, result, gait in zip(("G", "G moved"), results, gaits, strict=True):
        value, why = judged(robot, result, gait, motor, springs, contact)
        print(f"{label}: judged {value!r} J/m{why}, solver {result.energy_per_metre!r} J/m, "
              f"stationarity {result.stationarity:.3g}")
    def again(move: float) -> Any:
        return solve(robot, build_problem(robot, gaits[0], motor, springs, params), move=move)

    def read(result: Any) -> tuple[float | None, float, float]:
        value = judged(robot, result, gaits[0], motor, springs, contact)[0]
        return value, result.energy_per_metre, result.stationarity

    (spread,) = spreads(robot, [(read(results[0]), (), again, read)])
    print("the spread of G's solve (its start moved by "
          + ", ".join(f"{m:+.0e}" for m in spread.moves) + " m): judged "
          + ", ".join("—" if v is None else f"{v:.5f}" for v in spread.judged)
          + f" J/m, spread {spread.value:.2g} J/m; solver "
          + ", ".join(f"{v:.5f}" for v in spread.solver)
          + f", spread {spread.solver_value:.2g}; stationarity "
          + ", ".join(f"{v:.2g}" for v in spread.stationarity))
    print(f"wall {time.perf_counter() - began:.0f} s, CPU {time.process_time() - cpu:.0f} s "
          "(this process; the spread's solves in forked workers)")


if __name__ == "__main__":
    main()
