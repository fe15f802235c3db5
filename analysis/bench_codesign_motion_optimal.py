"""``hexaleg codesign --motion optimal`` run whole for a kept log: the command's output as printed
(stdout and stderr, each line time-stamped with ``--stamp``), ``/usr/bin/time -v``'s figures,
then what its codesign.json holds of each optimal row: its friction use and margin (issue #56's
"friction use ≤ 0.7 of the cone"), its spread, and its answers without and with the landing
cost, simulated, and which it kept (the worse servo's); and of each optimal motion its
dynamics residual by the check it names and its knots' defect. Logs:
analysis/bench_logs/codesign_motion_optimal_spread.log (the default robot),
analysis/bench_logs/codesign_motion_optimal_rk4.log (the default robot on RK4 knots:
``-- --config rk4.toml``, ``[codesign.optimal] integrator = "rk4"``),
analysis/bench_logs/codesign_motion_optimal_solo12.log's last two blocks (Solo-12, timing fixed
and searched). Minutes; it needs the optimal extra.

Run:  python analysis/bench_codesign_motion_optimal.py --out DIR [--stamp] [--rows]
          -- [codesign options]
e.g.  python analysis/bench_codesign_motion_optimal.py --out out
      python analysis/bench_codesign_motion_optimal.py --out out --stamp -- --robot solo12
          --speed 0.3 --config solo12.toml --feedback auto --timing search
(solo12.toml: ``[codesign] grouping = "mirrored"``).
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time

COMMAND = "import sys; from hexaleg.cli import main; sys.exit(main())"
"""hexaleg's command line in this interpreter (the one with the optimal extra)."""


def rows(data: dict) -> list[str]:
    """codesign.json's optimal rows: friction use against the margin, then the spread."""
    optimal = data["optimal"]
    margin = optimal["friction_margin"]["value"]
    out = [f"# codesign.json: optimal.rows[].friction_use (margin {margin:g}), "
           "optimal.rows[].spread"]
    for r in optimal["rows"]:
        use = r["friction_use"]["value"]
        said = ("no prediction" if use is None else f"friction use {use:.5f}, "
                + ("inside the margin" if r["within_margin"] else f"BEYOND: {r['beyond']}"))
        spread = r.get("spread")
        if spread is None:
            out.append(f"{r['label']}: no spread (not an optimal-control row); {said}")
            continue
        judged = ", ".join("—" if j["value"] is None else f"{j['value']:.5f}"
                           for j in spread["judged"])
        value = spread["value"]["value"]
        solver = ", ".join(f"{v:.5f}" for v in spread["solver"]["value"])
        stopped = ", ".join(f"{v:.2g}" for v in spread["stationarity"]["value"])
        out.append(f"{r['label']}: predicted {r['predicted']['value']:.5f} J/m, spread "
                   + ("—" if value is None else f"{value:.5f}") + f" J/m; judged {judged} J/m; "
                   f"solver {solver} J/m (spread {spread['solver_value']['value']:.5f}); "
                   f"stationarity {stopped}; {said}")
    for r in optimal["rows"]:
        landing = r.get("landing")
        if landing is None:
            continue
        out.append(f"{r['label']}: landing cost's answers (optimal.rows[].landing), kept "
                   f"{landing['kept']}: " + "; ".join(_answer(c) for c in landing["candidates"]))
    for key in ("no_springs", "springs_motion"):
        solved = optimal[key]
        check = solved.get("residual_check", "a check codesign.json does not name")
        defect = solved.get("defect")
        out.append(f"optimal.{key}: residual {solved['residual']['value']:.2g} N·m by {check}, "
                   "the knots' defect "
                   + ("not recorded" if defect is None else f"{defect['value']:.2g}")
                   + ", dynamic gap "
                   f"{solved['dynamic_gap']['value']:.2g}, {solved['iterations']} iterations")
    return out


def _answer(candidate: dict) -> str:
    """One answer of a row without or with the landing cost: weight, predicted, simulated."""
    predicted = candidate["predicted"]["value"]
    sims = ", ".join(f"{k} " + ("—" if v is None else f"{v['value']:.5f}")
                     for k, v in candidate["simulated"].items())
    return (f"weight {candidate['servo_landing_weight']['value']:g}: predicted "
            + ("—" if predicted is None else f"{predicted:.5f}") + f" J/m, simulated {sims}")


def main() -> int:
    """Run the command (module docstring); with ``--rows`` only print the rows of the run
    finished in ``--out``."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", required=True, help="the command's output folder")
    parser.add_argument("--stamp", action="store_true", help="time-stamp each line")
    parser.add_argument("--rows", action="store_true",
                        help="only print the rows of the run finished in --out")
    parser.add_argument("options", nargs="*", help="codesign's options after --")
    args = parser.parse_args()
    if args.rows:
        with open(os.path.join(args.out, "codesign.json"), encoding="utf-8") as f:
            print("\n".join(rows(json.load(f))), flush=True)
        return 0
    argv = ["/usr/bin/time", "-v", sys.executable, "-c", COMMAND, "codesign", "--motion",
            "optimal", *args.options, "--out", args.out]
    print(f"# {' '.join(argv[2:])}", flush=True)
    with subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                          env=os.environ | {"PYTHONUNBUFFERED": "1"}) as run:
        assert run.stdout is not None
        for line in run.stdout:
            stamp = time.strftime("%H:%M:%S ", time.gmtime()) if args.stamp else ""
            print(stamp + line, end="", flush=True)
    if run.returncode != 0:
        return run.returncode
    with open(os.path.join(args.out, "codesign.json"), encoding="utf-8") as f:
        print("\n".join(rows(json.load(f))), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
