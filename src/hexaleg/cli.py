"""The ``hexaleg`` command line: thin subcommands over the public API.

Each subcommand is a pair ``_add_<name>(subparsers)`` / ``_run_<name>(args)``; errors derived
from :class:`~hexaleg.errors.HexalegError` are printed as one line and exit with status 2.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence

from hexaleg import __version__
from hexaleg.errors import HexalegError


def _add_robot(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("robot", help="summary of the loaded robot model: links, masses, joints, "
                                     "limits, legs, poses")
    p.add_argument("--urdf", help="URDF file (default: the built-in hexaleg robot)")
    p.add_argument("--srdf", help="SRDF file with poses and disabled collision pairs")
    p.set_defaults(func=_run_robot)


def _run_robot(args: argparse.Namespace) -> int:
    from hexaleg.robot import load_robot

    robot = load_robot(args.urdf, args.srdf)
    print(robot.summary())
    return 0


def _add_motors(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("motors", help="servo catalogue: gear ratio, torque constant, resistance, "
                                      "gearbox efficiency, Joule coefficient, datasheet")
    p.add_argument("names", nargs="*", help="motor names (default: the whole catalogue)")
    p.set_defaults(func=_run_motors)


def _run_motors(args: argparse.Namespace) -> int:
    from hexaleg.motor import catalogue_table, motor

    print(catalogue_table({n: motor(n) for n in args.names} if args.names else None))
    return 0


SUBCOMMANDS = [_add_robot, _add_motors]
"""Parser builders, one per subcommand, in the order ``--help`` lists them."""


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="hexaleg",
        description="Whole-robot dynamics and energy analysis of legged robots with nonlinear "
                    "elastic joints.")
    parser.add_argument("--version", action="version", version=f"hexaleg {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for add in SUBCOMMANDS:
        add(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``hexaleg`` console script.

    Returns:
        Exit status: 0 on success, 2 on a hexaleg error (message on stderr).
    """
    parser = build_parser()
    args = parser.parse_args(argv)
    if not getattr(args, "func", None):
        parser.print_help()
        return 0
    try:
        return int(args.func(args) or 0)
    except HexalegError as e:
        print(f"hexaleg {args.command}: error: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
