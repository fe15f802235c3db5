"""The ``hexaleg view`` subcommand: its parser and its run (registered in
:data:`hexaleg.cli.SUBCOMMANDS`). The parser spells out the study's names
(:mod:`hexaleg.commands.view.study`, checked against them by its test) so that building it
imports neither the study nor meshcat.
"""

from __future__ import annotations

import argparse

from hexaleg.commands.options import add_motion_option
from hexaleg.robot.registry import ROBOT_HELP  # loaded by `import hexaleg` already


def add(sub: argparse._SubParsersAction) -> None:
    """Add ``view`` to the subcommands."""
    p = sub.add_parser("view", help="animate the gait, the sphere transformation or a simulated "
                                    "run in the browser (Meshcat): foot forces, joint colours")
    p.add_argument("--config", help="TOML file of 'hexaleg report' (gait, motor, contact, "
                                    "springs) with an optional [view] table")
    p.add_argument("--html", help="write a self-contained page that plays offline to this file "
                                  "and exit (default: serve the same page until Ctrl-C)")
    p.add_argument("--host", default="127.0.0.1",
                   help="the address to serve on (default %(default)s: this machine only; "
                        "0.0.0.0 for every network interface)")
    p.add_argument("--robot", help=ROBOT_HELP + " (with --simulation: default the file's)")
    # The names of hexaleg.commands.view.study's MOTIONS, JOINT_QUANTITIES and motion_file.RUNS,
    # which check them too (the study is not imported to build the parser: meshcat imports
    # slowly).
    p.add_argument("--simulation", metavar="DIR", help="replay a run of 'hexaleg simulate "
                                                       "--out DIR' instead (its motion files)")
    p.add_argument("--run", choices=("springs", "baseline"), help="with --simulation: the run "
                   "with the springs or without (default: springs)")
    p.add_argument("--joints", choices=("power", "torque", "spring"), default="power",
                   help="what colours the joints: motor power (W), motor torque or spring "
                        "torque (N·m) (default: %(default)s)")
    add_motion_option(p, run, None, ("gait", "transform"),
                      "gait (the tripod gait cycle, default), transform (stand → sphere) or a "
                      "log FILE of the robot's own gait (docs/motion.md)")


def run(args: argparse.Namespace) -> int:
    """Write the page (``--html``) or serve it until Ctrl-C."""
    from hexaleg.commands.view.study import export_view, serve_view, wait_until_interrupted

    shown = {k: getattr(args, k) for k in ("motion", "joints", "robot", "simulation", "run",
                                           "cycle")}
    shown["args"] = args
    if args.html:
        print(f"wrote {export_view(args.config, args.html, **shown)}")
        return 0
    url = serve_view(args.config, **shown, host=args.host)
    what = (f"{args.run or 'springs'} run of {args.simulation}" if args.simulation else
            args.motion or "gait")
    wait_until_interrupted(lambda: print(f"serving the {what} at {url} (Ctrl-C to stop)",
                                         flush=True))
    return 0


__all__ = ["add", "run"]
