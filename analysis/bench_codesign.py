"""Benchmark of ``hexaleg codesign`` on the default robot (issue #31: ≤ 120 s wall on a quiet
machine).

Run:  python analysis/bench_codesign.py [--rules]

Runs ``hexaleg codesign`` as a user does, a fresh process (imports included), into a temporary
directory, and prints its wall time and CPU share (the child's user + system CPU time over the
wall time, as bench_simulate.py and bench_design.py do): on the 2-core machine other busy
processes stretch the wall time, and a share well under 1 says by how much (the CPU time is then
the better estimate of a quiet run). ``--rules`` adds the full spring rules of ``hexaleg design``
on the chosen gait.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

TARGET = 120.0
"""Issue #31's target wall time, s."""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rules", action="store_true", help="with the full spring rules")
    args = parser.parse_args()
    exe = Path(sys.executable).with_name("hexaleg")
    with tempfile.TemporaryDirectory() as out:
        command = [str(exe), "codesign", "--out", out] + (["--rules"] if args.rules else [])
        before = os.times()
        start = time.perf_counter()
        subprocess.run(command, check=True, capture_output=True, cwd=out)
        wall = time.perf_counter() - start
        after = os.times()
    cpu = (after.children_user - before.children_user) + (after.children_system
                                                          - before.children_system)
    print(f"hexaleg codesign{' --rules' if args.rules else ''} (default robot, 0.06 m/s): "
          f"{wall:.1f} s wall (target <= {TARGET:.0f} s: {'met' if wall <= TARGET else 'not met'}"
          f"), {cpu:.1f} s CPU, CPU share {cpu / wall:.2f}")


if __name__ == "__main__":
    main()
