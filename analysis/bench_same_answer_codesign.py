"""``../shared/tools/same-answer`` on ``hexaleg codesign --motion optimal`` (issue #56's same
answer): the default robot's whole command run as given and with one input moved by 1e-9, the
two outputs diffed with timings masked (the tool's own run and mask); then the diff again without
the searches' and the solver's progress lines, and the optimal rows' figures of each run's
codesign.json. Log:
analysis/bench_logs/same_answer_codesign_motion_optimal.log (minutes: two whole commands a
move; not an example study: it needs the optimal extra).

Run:  python analysis/bench_same_answer_codesign.py [--tool ../shared/tools/same-answer]
                                              [--param body_high=1.300000001 ...]

The tool moves a ``[gait]`` parameter through ``--config``, and ``hexaleg codesign`` refuses a
``[gait]`` table (it searches the gait itself); its inputs of the same kind are ``[codesign]``'s.
So the command the tool runs is this script with ``--as-hexaleg``: hexaleg's command line with
the config's ``[gait]`` table read as ``[codesign]``, nothing else changed. The moves: the body
height's bound (``body_high``, × the default gait's body height: the co-design's chosen gait
stands at the bound, so its body height, and the optimal stage's start, move by 9e-11 m) and
the speed (every gait and knot moves).
"""

from __future__ import annotations

import argparse
import difflib
import json
import os
import re
import subprocess
import sys
import tempfile

PARAMS = ("body_high=1.300000001", "speed=0.060000001")
"""The default moves (module docstring)."""


def as_hexaleg(argv: list[str]) -> int:
    """hexaleg's command line, a ``--config`` file's ``[gait]`` table read as ``[codesign]``."""
    from hexaleg.cli import main

    args = list(argv)
    if "--config" in args:
        at = args.index("--config") + 1
        with open(args[at], encoding="utf-8") as f:
            text = f.read().replace("[gait]\n", "[codesign]\n")
        fd, name = tempfile.mkstemp(suffix=".toml")
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            f.write(text)
        args[at] = name
    return int(main(args) or 0)


MASK = (re.compile(r"\(?[0-9]+(\.[0-9]+)? ?s( wall)?\)?"), re.compile(r"[0-9.]+ s\b"))
"""The tool's mask of timings (its ``sed``), to diff its two outputs again here."""

PROGRESS = re.compile(r"search: run|: iteration [0-9]+:")
"""The searches' and the solver's progress lines, left out of the second diff."""


def masked(path: str) -> list[str]:
    """A kept output's lines with the tool's timings masked."""
    with open(path, encoding="utf-8") as f:
        lines = f.read().splitlines()
    return [MASK[1].sub("", MASK[0].sub("", line)) for line in lines]


def figures(directory: str, label: str) -> None:
    """The optimal rows' figures behind the printed digits, from codesign.json."""
    with open(os.path.join(directory, "out", "codesign.json"), encoding="utf-8") as f:
        rows = json.load(f)["optimal"]["rows"]
    for r in rows[2:]:
        spread = r.get("spread") or {"value": {"value": float("nan")}}
        sims = ", ".join(f"{k} {v['value']:.4f}" if v else f"{k} —"
                         for k, v in r["simulated"].items())
        print(f"{label}: {r['label']}: predicted {r['predicted']['value']:.5f} J/m (spread "
              f"{spread['value']['value']:.5f}), simulated {sims}")


def main() -> int:
    if sys.argv[1:2] == ["--as-hexaleg"]:
        return as_hexaleg(sys.argv[2:])
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--tool", default=os.path.join(os.path.dirname(__file__), "..", "..",
                                                       "shared", "tools", "same-answer"))
    parser.add_argument("--param", action="append", default=None)
    args = parser.parse_args()
    worst = 0
    for param in args.param or PARAMS:
        print(f"$ same-answer --param {param} -- hexaleg codesign --motion optimal", flush=True)
        done = subprocess.run([args.tool, "--param", param, "--", sys.executable,
                               os.path.abspath(__file__), "--as-hexaleg", "codesign",
                               "--motion", "optimal"], check=False, capture_output=True,
                              text=True)
        print(done.stdout + done.stderr, end="")
        print(f"exit {done.returncode}", flush=True)
        worst = max(worst, done.returncode)
        kept = re.search(r"\(outputs in (\S+)\):", done.stdout)
        if kept is None:
            continue
        work = kept[1]
        print(f"-- {param}: the diff without progress lines:")
        for line in difflib.unified_diff(masked(os.path.join(work, "a.txt")),
                                         masked(os.path.join(work, "b.txt")), n=0,
                                         lineterm=""):
            if line[:1] in "+-" and line[:3] not in ("+++", "---") and not PROGRESS.search(line):
                print(line)
        print(f"-- {param}: the optimal rows' figures (codesign.json):")
        figures(os.path.join(work, "a"), "as given")
        figures(os.path.join(work, "b"), "moved")
    return worst


if __name__ == "__main__":
    sys.exit(main())
