"""Benchmark per robot (#26, #39): ``hexaleg design`` wall time and memory and the simulation's
speed, on every registered robot and the test robots, as ratios against the default robot in the
same process.

Run:  nice python analysis/bench_robots.py [--robots hexaleg solo12 …] [--no-design]

For each robot, one row:

* design: the wall time of ``hexaleg design --robot R`` in this process (``write_design`` with
  the robot's defaults, into a temporary directory; imports and the first-use compilation are
  paid by the default robot, measured first), the gait the defaults chose, the recommendation
  and its saving net of the springs' mass, and the two slowest stages. Target ≤ 60 s.
* simulate: ``hexaleg simulate --robot R --cycles 4``'s two runs (with the optimal linear springs
  and without), simulated seconds per wall-clock second of their stepping, and the timestep
  the simulation chose (``simulation.stepping``). Target ≥ 10× real time.
* memory: the peak resident memory of this process and of its largest child (the design's forked
  workers) so far, MB (``resource.getrusage``: peaks, so a row's figure is at least the rows'
  before it). Target ≤ 1 GB.
* the ratio of each to the default robot's, so that a loaded machine (both slow down alike) still
  compares robots. The CPU share (this process's CPU time over the wall time) says how loaded.

A design or simulation that ends in a hexaleg error is a row with the error, not an exception (a
design that ends in any other exception, a bug, is a row marked BUG).
"""

from __future__ import annotations

import argparse
import resource
import sys
import tempfile
import time
from pathlib import Path

from hexaleg.commands.design.write import write_design
from hexaleg.commands.simulate.study import load_study
from hexaleg.errors import HexalegError
from hexaleg.robot.registry import DESCRIPTIONS
from hexaleg.scenario.scenario import Scenario

TEST_ROBOTS = {name: str(Path(__file__).resolve().parents[1] / "tests" / "data" /
                        f"{name}.toml") for name in ("spider", "xquad", "quad2dof", "quad4dof",
                                                        "biped")}
"""The test robots by short name → TOML."""
DESIGN_TARGET = 60.0
"""``hexaleg design`` wall time target, s."""
SIMULATE_TARGET = 10.0
"""Simulation speed target, × real time."""


def design_time(robot: str) -> tuple[float, str]:
    """Wall time of the design, s, and its outcome in a few words."""
    t0 = time.perf_counter()
    with tempfile.TemporaryDirectory() as out:
        try:
            r = write_design(out, Scenario.load(robot), progress=None).result
            slowest = sorted(r.timings.items(), key=lambda kv: -kv[1])[:2]
            g, m, rec = r.gait, r.design.metric, r.recommended
            what = (f"gait {g.period:.3g} s / stride {1e3 * g.stride:.3g} mm / step "
                    f"{1e3 * g.step_height:.3g} mm; recommended {rec.label} on "
                    f"{', '.join(rec.optimum.groups)}: {m} {100 * rec.net[m]:+.2f} % net "
                    "(slowest stages: "
                    + ", ".join(f"{k} {v:.0f} s" for k, v in slowest) + ")")
        except HexalegError as err:
            what = f"{type(err).__name__}: {str(err)[:80]}"
        except Exception as err:  # a bug: recorded in its row
            what = f"BUG {type(err).__name__}: {str(err)[:80]}"
    return time.perf_counter() - t0, what


def simulate_speed(robot: str) -> tuple[float, float, str]:
    """Real-time factor of the two runs' stepping, the timestep (s), the verdict."""
    try:
        study = load_study(Scenario.load(robot), overrides={"cycles": 4})
        s = study.run()
    except HexalegError as err:
        return float("nan"), float("nan"), f"{type(err).__name__}: {str(err)[:80]}"
    runs = (s.with_springs, s.baseline)
    wall = sum(r.wall for r in runs)
    factor = sum(r.simulated_time for r in runs) / wall if wall > 0 else float("inf")
    return factor, s.with_springs.sim.timestep, "walks" if s.walks else "did not walk"


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--robots", nargs="*", default=[*DESCRIPTIONS, *TEST_ROBOTS])
    parser.add_argument("--no-design", dest="design", action="store_false")
    args = parser.parse_args()
    wall0, cpu0 = time.perf_counter(), time.process_time()
    print(f"{'robot':<9} {'design s':>9} {'x default':>9} {'sim xRT':>8} {'x default':>9} "
          f"{'dt us':>7} {'peak MB':>8}  outcome")
    ref: dict[str, float] = {}
    for name in ["hexaleg", *(r for r in args.robots if r != "hexaleg")]:
        robot = TEST_ROBOTS.get(name, name)
        wall, what = design_time(robot) if args.design else (float("nan"), "design skipped")
        factor, dt, verdict = simulate_speed(robot)
        ref.setdefault("design", wall)
        ref.setdefault("simulate", factor)
        peak = max(resource.getrusage(who).ru_maxrss for who in
                   (resource.RUSAGE_SELF, resource.RUSAGE_CHILDREN)) / 1024  # kB on Linux
        flags = [f for f, bad in (("design over 60 s", wall > DESIGN_TARGET),
                                  ("simulation under 10x", factor < SIMULATE_TARGET),
                                  ("over 1 GB", peak > 1024)) if bad]
        print(f"{name:<9} {wall:9.1f} {wall / ref['design']:9.2f} {factor:8.1f} "
              f"{factor / ref['simulate']:9.2f} {dt * 1e6:7.1f} {peak:8.0f}  {verdict}; {what}"
              + (f"  [{', '.join(flags)}]" if flags else ""), flush=True)
    share = (time.process_time() - cpu0) / (time.perf_counter() - wall0)
    print(f"CPU share of this process: {share:.2f} (below ~0.9: the machine was busy; the "
          "design's family workers run in child processes and are not counted)")


if __name__ == "__main__":
    sys.exit(main())
