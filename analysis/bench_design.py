"""Benchmark of the spring design program: the whole robot's optimal springs in one convex solve.

Run:  python analysis/bench_design.py [--samples 1000] [--repeat 5]

For the default tripod gait and three class groups (coxa, femur, tibia; joule objective, one shared
design per class) it times, at a fixed geometry, the fast path (condensed active set,
:func:`hexaleg.design.search.program.solve_design`) and the cvxpy reference
(:func:`hexaleg.design.search.program_reference.solve_design_reference`) on the same program, on a
floor where no inequality binds (μ = 0.6) and where the friction cones bind (μ = 0.3, the paper's
Table 3 static friction), and prints their ratio and agreement; then the whole ``optimal_springs``
call with the geometry searched, and one stop's exhaustive scan with its bounds against every
candidate solved (:func:`scan_ratio`). Targets (issue "Springs as decision variables"): ≤ 50 ms when
nothing binds, ≤ 2 s otherwise. Last, the wall time of the two commands a user runs, each a fresh
process (imports included): ``hexaleg design`` with its maps and robust design (target ≤ 30 s,
issues "The design answer" and #30) and ``hexaleg report`` (≤ 8 s), and ``hexaleg design``'s
pipeline in this process stage by stage (``DesignChain.run``), wall and CPU time per stage. Each
line gives its CPU share (CPU time / wall time, as bench_simulate.py does): on the 2-core machine
other busy processes stretch the wall time, and a share well under 1 says by how much (the CPU time
is then the better estimate of a quiet run).

``--stages`` runs only the last part (the pipeline by stage and the two commands).
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Callable
from functools import partial
from typing import Any

import numpy as np

import hexaleg
from hexaleg.design.search.optimal import design_problem, optimal_springs
from hexaleg.design.search.program import solve_design
from hexaleg.design.search.program_reference import solve_design_reference

CLASSES = ["coxa", "femur", "tibia"]
GEOMETRY = {"linear": {}, "dead_zone": {"theta_minus": -0.1, "theta_plus": 0.05}}


def _best(fn: Callable[[], Any], repeat: int) -> tuple[float, Any]:
    best, out = np.inf, None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=1000)
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--stages", action="store_true",
                        help="only hexaleg design by stage and the commands' wall times")
    args = parser.parse_args()
    if args.stages:
        return
    robot = hexaleg.load()
    motion = hexaleg.gait(robot, hexaleg.GaitParams(samples=args.samples))
    print(f"default tripod gait, {motion.n_samples} samples per cycle, 3 class groups, joule")
    for mu in (0.6, 0.3):
        prepared = hexaleg.prepare(robot, motion, contact=hexaleg.ContactParams(mu=mu))
        prepared.baseline()  # the gains and the baseline: once per gait, as in a study
        for fam, g in GEOMETRY.items():
            problem = design_problem(prepared, CLASSES, fam, {c: g for c in CLASSES})
            t_fast, fast = _best(partial(solve_design, problem), args.repeat)
            t_ref, ref = _best(partial(solve_design_reference, problem), 1)
            rel = abs(fast.value - ref.value) / ref.value
            print(f"μ = {mu}  {fam:<9}  fast {1e3 * t_fast:8.1f} ms ({fast.rounds} solves, "
                  f"{fast.explicit.size:4d} explicit samples)   cvxpy {1e3 * t_ref:8.1f} ms   "
                  f"ratio {t_ref / t_fast:6.1f} x   |Δvalue|/value {rel:.1e}   "
                  f"max |Δx| {np.abs(fast.x - ref.x).max():.1e}")
    prepared = hexaleg.prepare(robot, motion)
    scan_ratio(prepared)
    for fam in ("linear", "dead_zone", "preloaded", "one_sided"):
        t, res = _best(partial(optimal_springs, prepared, CLASSES, fam), 1)
        print(f"optimal_springs {fam:<9} geometry searched: {t:6.2f} s, "
              f"{res.solver['geometry_evaluations']:4d} convex solves, joule saving "
              f"{100 * res.saving:+.2f} %, electrical "
              f"{100 * res.analysis.savings['total']['electrical']:+.2f} %")


def scan_ratio(prepared: hexaleg.Prepared) -> None:
    """One exhaustive scan of a stop (the femur's one-sided contact, both sides, every coxa,
    femur and tibia class sprung; :mod:`hexaleg.design.search.geometry`): every candidate solved
    exactly against the lower bounds at all candidates at once (:mod:`hexaleg.design.search.scan`)
    and exact solves only where a bound can win; the same minimum, the ratio of their times."""
    from hexaleg.design.search.geometry import search_value
    from hexaleg.design.search.scan import relaxed_values
    from hexaleg.design.search.setup import design_setup

    setup = design_setup(prepared, CLASSES, "one_sided", "joule", None, np.pi)
    value = search_value(setup)
    state = {"coxa": {"contact": 0.5, "side": "above"}, "tibia": {"contact": 0.19,
                                                                  "side": "below"}}
    r = prepared.q[:, [prepared.robot.column(j) for j in prepared.robot.joints("femur")]]
    r = np.unique((r - (r.min(0) + r.max(0)) / 2).ravel())
    sides = {"above": r - 1e-8, "below": r + 1e-8}

    def every() -> float:
        return min(value({**state, "femur": {"contact": float(c), "side": s}})
                   for s, cs in sides.items() for c in cs)

    def bounded() -> float:
        best = np.inf
        for s, cs in sides.items():
            start = {**state, "femur": {"contact": float(cs[0]), "side": s}}
            bounds = relaxed_values(setup, start, "femur", "contact", cs, s)
            for n in np.argsort(bounds, kind="stable"):
                if bounds[n] >= best * (1 - 1e-9):
                    break
                best = min(best, value({**state, "femur": {"contact": float(cs[n]),
                                                           "side": s}}))
        return best

    t_every, v_every = _best(every, 1)
    t_bounded, v_bounded = _best(bounded, 3)
    print(f"one stop scanned over {2 * r.size} places: every place solved {t_every:6.2f} s, "
          f"bounded {t_bounded:6.2f} s, ratio {t_every / t_bounded:5.1f} x, same minimum "
          f"to {abs(v_every - v_bounded) / v_every:.1e}")


def _wall(args: list[str]) -> tuple[float, float]:
    """Wall and CPU time (user + system) of ``hexaleg ARGS`` in a fresh process, s."""
    import os
    import subprocess
    import sys
    import tempfile

    with tempfile.TemporaryDirectory() as out:
        before, t0 = os.times(), time.perf_counter()
        subprocess.run([sys.executable, "-m", "hexaleg.cli", *args, "--out", out], check=True,
                       capture_output=True)
        wall, after = time.perf_counter() - t0, os.times()
    return wall, (after.children_user - before.children_user
                  + after.children_system - before.children_system)


DESIGN_TARGET = 30.0
"""s wall of ``hexaleg design`` on the default robot on a quiet machine (issue #30)."""


def stages() -> None:
    """``hexaleg design``'s pipeline (``DesignChain().run()``, default robot) in this process:
    wall and CPU time of each stage, its CPU share, and the total against the target."""
    from hexaleg.design.chain.chain import DesignChain

    marks: list[tuple[float, float]] = []
    marks.append((time.perf_counter(), time.process_time()))
    result = DesignChain(progress=lambda _msg: marks.append((time.perf_counter(),
                                                              time.process_time()))).run()
    print("hexaleg design by stage (DesignChain.run, default robot; this process)")
    print(f"  {'stage':<18} {'wall s':>7} {'CPU s':>7} {'CPU share':>9}")
    for name, (w0, c0), (w1, c1) in zip(result.timings, marks[:-1], marks[1:], strict=True):
        print(f"  {name:<18} {w1 - w0:7.2f} {c1 - c0:7.2f} {(c1 - c0) / (w1 - w0):9.2f}")
    wall, cpu = marks[-1][0] - marks[0][0], marks[-1][1] - marks[0][1]
    print(f"  {'total':<18} {wall:7.2f} {cpu:7.2f} {cpu / wall:9.2f}   (target ≤ "
          f"{DESIGN_TARGET:g} s wall on a quiet machine"
          + ("" if cpu / wall > 0.9 else f"; busy machine: CPU time {cpu:.1f} s is the better "
             "estimate") + ")")


def commands() -> None:
    """The wall time of ``hexaleg design`` and ``hexaleg report`` on the default robot, each a
    fresh process (imports included), with its CPU share."""
    for name, target in (("design", DESIGN_TARGET), ("report", 8.0)):
        wall, cpu = _wall([name])
        print(f"hexaleg {name:<7} {wall:6.1f} s wall, {cpu:6.1f} s CPU (CPU share "
              f"{cpu / wall:.2f}; target ≤ {target:g} s wall on a quiet machine)")


if __name__ == "__main__":
    main()
    stages()
    commands()
