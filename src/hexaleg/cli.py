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


def _add_paper(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("paper", help="reproduce the paper's single elastic joint: paper.json, "
                                     "Fig. 5-13 analogues (PNG), summary.md")
    p.add_argument("--out", default="paper-report", help="output directory (default: %(default)s)")
    p.add_argument("--samples", type=int, default=8192,
                   help="samples per trajectory period (default: %(default)s)")
    p.set_defaults(func=_run_paper)


def _run_paper(args: argparse.Namespace) -> int:
    from hexaleg.paper import write_report

    r = write_report(args.out, n=args.samples)
    print(f"k_M = {r['k_M_paper_units']:.3f} (paper's eq. 19 units) = "
          f"{r['k_M_SI_Nm_per_rad']:.4e} N·m/rad; k_E: {r['k_E']['verdict']}; "
          f"52.81%: {r['saving_52_81']['verdict']}")
    print(f"wrote {args.out}/paper.json, summary.md and figures")
    return 0


def _add_gait(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("gait", help="the tripod gait: parameters, static margin, joint ranges, "
                                    "peak joint speeds and accelerations")
    p.add_argument("--config", help="TOML file with a [gait] table (default: GaitParams())")
    p.set_defaults(func=_run_gait)


def _run_gait(args: argparse.Namespace) -> int:
    from hexaleg.gait import GaitParams, gait_summary, tripod_gait
    from hexaleg.robot import load_robot

    robot = load_robot()
    gait = GaitParams.from_toml(args.config) if args.config else GaitParams()
    print(gait_summary(robot, tripod_gait(robot, gait)))
    return 0


SUBCOMMANDS = [_add_robot, _add_motors, _add_gait, _add_paper]
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
