"""The ``hexaleg gait`` subcommand: the run's gait — its parameters, static margin, joint ranges,
peak joint speeds and accelerations (:func:`hexaleg.outputs.text.gait_summary`) — and the run's
warnings; registered in :data:`hexaleg.cli.SUBCOMMANDS`.
"""

from __future__ import annotations

import argparse

from hexaleg.commands.options import print_findings, print_warnings
from hexaleg.robot.registry import ROBOT_HELP  # loaded by `import hexaleg` already


def add(sub: argparse._SubParsersAction) -> None:
    """Add ``gait`` to the subcommands."""
    p = sub.add_parser("gait", help="the tripod gait: parameters, static margin, joint ranges, "
                                    "peak joint speeds and accelerations")
    p.add_argument("--config", help="TOML file with a [gait] table; its keys replace those of "
                                    "the robot's gait (its description's, the keys it leaves "
                                    "unset sized to it: docs/robots.md)")
    p.add_argument("--robot", default="hexaleg", help=ROBOT_HELP + " (default %(default)s)")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    """``hexaleg gait``: the gait's summary, the run's warnings, then the sanity checks' other
    findings."""
    from hexaleg.commands.options import load_run
    from hexaleg.motion.sanity import motion_findings
    from hexaleg.outputs.text import gait_summary
    from hexaleg.robot.sanity import robot_findings

    run = load_run(args.robot, args.config)
    motion = run.motion()
    print(gait_summary(run.model, motion))
    warned = run.warnings(motion)
    print_warnings(warned)  # the same lines as report, design and simulate say for this run
    print_findings([f for f in (*robot_findings(run.model), *motion_findings(run.model, motion))
           if f.message not in warned])
    return 0


__all__ = ["add", "run"]
