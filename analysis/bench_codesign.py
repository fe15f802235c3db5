"""Benchmark of ``hexaleg codesign`` on the default robot (issue #31: ≤ 120 s wall on a quiet
machine), the full spring rules included (the default).

Run:  python analysis/bench_codesign.py [--no-rules]

Runs ``hexaleg codesign`` as a user does, a fresh process (imports included), into a temporary
directory, and prints its wall time against the target (their ratio) and its CPU share (the
child's and its workers' user + system CPU time over the wall time, as bench_simulate.py and
bench_design.py do): on the 2-core machine other busy processes stretch the wall time, and a
share well under 1 says by how much (the CPU time is then the better estimate of a quiet run;
the families of the rules run in two worker processes, so a quiet run's wall time is a little
under its CPU time). Then the stages as ``codesign.json`` records them — the two searches, the
rows, curve and simulation, and each stage of the full rules — with their share of the run.
``--no-rules`` times the search's answer alone.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

TARGET = 120.0
"""Issue #31's target wall time, s."""


def stages(data: dict) -> dict[str, float]:
    """Stage → wall time, s, from ``codesign.json``: the two searches, each stage of the rules
    (the ``family …`` stages summed: they run in parallel, each timed to its end) and the rest
    of the run. The rules run in a process of their own from the end of the co-design search,
    beside the gait-alone search, the rows and the curve, so the rest is the run's wall time
    less the co-design search and the rules: the simulation, and whatever of the work beside
    the rules outlasted them (without the rules: the rows, the curve and the simulation)."""
    out = {f"search ({name})": s["wall"]["value"] for name, s in data["search"].items()}
    rules = data["full_rules"] or {}
    timings = {k: v["value"] for k, v in rules.get("timings", {}).items()}
    if timings:
        out["rules: families"] = sum(v for k, v in timings.items() if k.startswith("family "))
        out.update({f"rules: {k}": v for k, v in timings.items() if not k.startswith("family ")})
        parallel = out["search (gait)"]
    else:
        parallel = 0.0
    out["rest"] = data["wall"]["value"] - sum(out.values()) + parallel
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--no-rules", action="store_true", help="without the full spring rules")
    args = parser.parse_args()
    exe = Path(sys.executable).with_name("hexaleg")
    with tempfile.TemporaryDirectory() as out:
        command = [str(exe), "codesign", "--out", out] + (["--no-rules"] if args.no_rules
                                                          else [])
        before = os.times()
        start = time.perf_counter()
        subprocess.run(command, check=True, capture_output=True, cwd=out)
        wall = time.perf_counter() - start
        after = os.times()
        data = json.loads((Path(out) / "codesign.json").read_text())
    cpu = (after.children_user - before.children_user) + (after.children_system
                                                          - before.children_system)
    print(f"hexaleg codesign{' --no-rules' if args.no_rules else ''} (default robot, 0.06 m/s): "
          f"{wall:.1f} s wall, {wall / TARGET:.2f} of the {TARGET:.0f} s target "
          f"({'met' if wall <= TARGET else 'not met'} on this machine); {cpu:.1f} s CPU "
          f"({cpu / TARGET:.2f} of the target), CPU share {cpu / wall:.2f}")
    total = data["wall"]["value"]
    print(f"stages in the process ({total:.1f} s; imports and writing the files: "
          f"{wall - total:.1f} s; the rules beside the gait-alone search):")
    for name, seconds in stages(data).items():
        print(f"  {name:28s} {seconds:6.1f} s  {seconds / total:5.2f}")


if __name__ == "__main__":
    main()
