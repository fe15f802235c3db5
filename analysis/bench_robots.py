"""Benchmark per robot (#26, #39, #55): ``hexaleg design`` (and ``hexaleg codesign``) wall time,
CPU time and peak memory, and the simulation's speed, on every registered robot and the test
robots, as ratios against the default robot measured in the same run.

Run:  nice python analysis/bench_robots.py [--robots hexaleg solo12 …] [--no-design]
          [--codesign] [--config F] [--timeout 1200]

For each robot, one row:

* design: ``hexaleg design --robot R`` run in a fresh child process (its own imports, caches and
  memory; the command line exactly as a user types it, into a temporary directory): its wall
  time, its CPU time with its forked family workers', and its peak resident memory (the most of
  the child's own and of its largest worker: ``resource.getrusage`` at its end). The three
  slowest stages (``DesignResult.timings``, from design.json), the recommendation and the
  outcome. Targets ≤ 60 s and ≤ 1 GB (issue #55, on a quiet 2-core machine).
* codesign (``--codesign``): the same for ``hexaleg codesign --robot R --no-rules``. Targets
  ≤ 5 min and ≤ 2 GB.
* simulate: ``hexaleg simulate --robot R --cycles 4``'s two runs (with the optimal linear springs
  and without), simulated seconds per wall-clock second of their stepping, and the timestep the
  simulation chose (``simulation.stepping``). Target ≥ 10× real time. In this process.
* the ratio of each time to the default robot's, so that a loaded machine (both slow down alike)
  still compares robots; and the child's CPU share (CPU time over wall time: up to 2 with both
  cores busy; well below 1, the machine was busy).

``--config F`` passes ``--config F`` to each design and codesign command of the run, the
default robot's included (not to the simulate row, run in this process): the brushless
hexapod's co-design at its default speed needs ``[codesign.constraints] friction_margin = 1``
(at 0.7 its default gait is refused, naming that key).

Its last rows, before and after a change, are kept in ``analysis/bench_logs/bench_robots.log``.

A command that ends in a hexaleg error (exit 2) is a row with its ``error:`` line; one that ends
in a traceback is a row marked BUG; one over ``--timeout`` is killed (its process group) and
marked so.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

from hexaleg.cli import main as cli
from hexaleg.commands.simulate.study import load_study
from hexaleg.errors import HexalegError
from hexaleg.robot.registry import DESCRIPTIONS
from hexaleg.scenario.scenario import Scenario

TEST_ROBOTS = {name: str(Path(__file__).resolve().parents[1] / "tests" / "data" /
                        f"{name}.toml") for name in ("spider", "xquad", "quad2dof", "quad4dof",
                                                        "biped", "humanoid", "wheeled", "pryquad",
                                                        "bldc_hexapod")}
"""The test robots by short name → TOML."""
TARGETS = {"design": (60.0, 1024.0), "codesign": (300.0, 2048.0)}
"""Command → (wall time target s, peak memory target MB) (issue #55)."""
SIMULATE_TARGET = 10.0
"""Simulation speed target, × real time."""


def child(command: str, robot: str, config: str | None = None) -> None:
    """In the child process: run ``hexaleg <command> --robot <robot> [--config <config>]`` into a
    temporary directory and print one JSON line: wall and CPU time (s, the forked workers'
    included), peak memory (MB: this process's and its largest worker's), exit code, the last
    stderr line when it failed, and the stages' timings."""
    import contextlib
    import io

    t0 = time.perf_counter()
    err = io.StringIO()
    with tempfile.TemporaryDirectory() as out:
        argv = [command, "--robot", robot, "--out", str(Path(out) / command)]
        if command == "codesign":
            argv.append("--no-rules")
        if config:
            argv += ["--config", config]
        with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
            try:
                rc = cli(argv)
            except Exception as exc:  # a bug: recorded in its row
                rc, last = -1, f"BUG {type(exc).__name__}: {exc}"
            else:
                lines = [ln for ln in err.getvalue().splitlines() if ln.strip()]
                last = lines[-1] if rc and lines else ""
        wall = time.perf_counter() - t0
        found = list(Path(out).glob(f"{command}/*.json"))
        data = json.loads(found[0].read_text()) if command == "design" and found else {}
    usage = {who: resource.getrusage(who) for who in (resource.RUSAGE_SELF,
                                                     resource.RUSAGE_CHILDREN)}
    result = data.get("result", data)
    timings = {k: v["value"] for k, v in result.get("timings", {}).items()}
    rec = result.get("recommended", {})
    print(json.dumps({
        "wall": wall, "rc": rc, "last": last, "timings": timings,
        "cpu": sum(u.ru_utime + u.ru_stime for u in usage.values()),
        "peak_self": usage[resource.RUSAGE_SELF].ru_maxrss / 1024,  # kB on Linux
        "peak_workers": usage[resource.RUSAGE_CHILDREN].ru_maxrss / 1024,
        "recommended": rec.get("label", "") if isinstance(rec, dict) else ""}))


def measure(command: str, robot: str, timeout: float,
            config: str | None = None) -> dict[str, Any]:
    """``hexaleg <command> --robot <robot> [--config <config>]`` in a fresh child process
    (:func:`child`), killed with its workers after ``timeout`` s."""
    t0 = time.perf_counter()
    proc = subprocess.Popen([sys.executable, __file__, "--child", command, robot,
                             *(["--config", str(Path(config).resolve())] if config else [])],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            start_new_session=True, env=os.environ.copy())
    try:
        out, err = proc.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.communicate()
        return {"wall": time.perf_counter() - t0, "rc": None, "cpu": float("nan"),
                "peak_self": float("nan"), "peak_workers": float("nan"), "timings": {},
                "last": f"killed after {timeout:.0f} s", "recommended": ""}
    lines = out.strip().splitlines()
    if proc.returncode or not lines:
        return {"wall": time.perf_counter() - t0, "rc": -1, "cpu": float("nan"),
                "peak_self": float("nan"), "peak_workers": float("nan"), "timings": {},
                "last": f"BUG child exited {proc.returncode}: {err.strip()[-200:]}",
                "recommended": ""}
    row: dict[str, Any] = json.loads(lines[-1])
    return row


def outcome(command: str, row: dict[str, Any]) -> str:
    """A row's measures and outcome in a few words, with the targets it misses."""
    wall_target, peak_target = TARGETS[command]
    peak = max(row["peak_self"], row["peak_workers"])
    slowest = sorted(row["timings"].items(), key=lambda kv: -kv[1])[:3]
    what = ("ok" if row["rc"] == 0 else row["last"][:100]) + (
        f", recommended {row['recommended']}" if row["recommended"] else "") + (
        " (slowest stages: " + ", ".join(f"{k} {v:.0f} s" for k, v in slowest) + ")"
        if slowest else "")
    flags = [f for f, bad in ((f"over {wall_target:.0f} s", row["wall"] > wall_target),
                              (f"over {peak_target:.0f} MB", peak > peak_target)) if bad]
    return what + (f"  [{', '.join(flags)}]" if flags else "")


def simulate_speed(robot: str) -> tuple[float, float, str]:
    """Real-time factor of the two runs' stepping, the timestep (s), the verdict."""
    try:
        study = load_study(Scenario.load(robot), overrides={"cycles": 4})
        s = study.run()
    except HexalegError as err:
        return float("nan"), float("nan"), f"{type(err).__name__}: {str(err)[:80]}"
    runs = (s.with_springs, s.baseline)
    wall = s.stepping_wall  # the two runs step side by side: their spans' union
    factor = sum(r.simulated_time for r in runs) / wall if wall > 0 else float("inf")
    return factor, s.with_springs.sim.timestep, "walks" if s.walks else "did not walk"


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--robots", nargs="*", default=[*DESCRIPTIONS, *TEST_ROBOTS])
    parser.add_argument("--no-design", dest="design", action="store_false")
    parser.add_argument("--codesign", action="store_true")
    parser.add_argument("--no-simulate", dest="simulate", action="store_false")
    parser.add_argument("--config", help="a TOML file passed to every command (--config F)")
    parser.add_argument("--timeout", type=float, default=1200.0)
    parser.add_argument("--child", nargs=2, metavar=("COMMAND", "ROBOT"), help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child:
        child(*args.child, config=args.config)
        return
    commands = [c for c, on in (("design", args.design), ("codesign", args.codesign)) if on]
    print(f"{'robot':<12} {'command':<9} {'wall s':>7} {'x default':>9} {'CPU s':>7} "
          f"{'share':>5} {'peak MB':>8} {'worker MB':>9}  outcome")
    ref: dict[str, float] = {}
    for name in ["hexaleg", *(r for r in args.robots if r != "hexaleg")]:
        robot = TEST_ROBOTS.get(name, name)
        for command in commands:
            row = measure(command, robot, args.timeout, args.config)
            ref.setdefault(command, row["wall"])
            print(f"{name:<12} {command:<9} {row['wall']:7.1f} {row['wall'] / ref[command]:9.2f} "
                  f"{row['cpu']:7.1f} {row['cpu'] / row['wall']:5.2f} {row['peak_self']:8.0f} "
                  f"{row['peak_workers']:9.0f}  {outcome(command, row)}", flush=True)
        if args.simulate:
            factor, dt, verdict = simulate_speed(robot)
            ref.setdefault("simulate", factor)
            print(f"{name:<12} {'simulate':<9} {factor:7.1f} xRT {factor / ref['simulate']:5.2f} "
                  f"x default, dt {dt * 1e6:.1f} us: {verdict}"
                  + ("  [under 10x]" if factor < SIMULATE_TARGET else ""), flush=True)


if __name__ == "__main__":
    main()
