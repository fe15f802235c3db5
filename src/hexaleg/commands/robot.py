"""The ``hexaleg robot`` subcommand: the summary of a loaded robot model (links, masses, joints,
limits, legs, poses) and its sanity checks' findings (:mod:`hexaleg.robot.sanity`); registered in
:data:`hexaleg.cli.SUBCOMMANDS`.
"""

from __future__ import annotations

import argparse

from hexaleg.commands.options import print_findings
from hexaleg.errors import InvalidParameterError
from hexaleg.robot.registry import ROBOT_HELP  # loaded by `import hexaleg` already


def add(sub: argparse._SubParsersAction) -> None:
    """Add ``robot`` to the subcommands."""
    p = sub.add_parser("robot", help="summary of the loaded robot model: links, masses, joints, "
                                     "limits, legs, poses")
    p.add_argument("--urdf", help="URDF file (default: the built-in hexaleg robot)")
    p.add_argument("--srdf", help="SRDF file with poses and disabled collision pairs")
    p.add_argument("--robot", help=ROBOT_HELP + " instead of --urdf/--srdf")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    """``hexaleg robot``: the robot's summary, then its sanity checks' findings as warnings."""
    from hexaleg.robot.model import load_robot
    from hexaleg.robot.registry import load
    from hexaleg.robot.sanity import robot_findings

    if args.robot is not None and (args.urdf or args.srdf):
        raise InvalidParameterError("--robot", args.robot, "either --robot or --urdf/--srdf")
    robot = load(args.robot) if args.robot is not None else load_robot(args.urdf, args.srdf)
    print(robot.summary())
    print_findings(robot_findings(robot))
    return 0


__all__ = ["add", "run"]
