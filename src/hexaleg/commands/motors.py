"""The ``hexaleg motors`` subcommand: the servo catalogue, or (``--identify LOG``) the robot's
actuators fitted to a log of its own gait (:mod:`hexaleg.dynamics.identification`); registered
in :data:`hexaleg.cli.SUBCOMMANDS`.
"""

from __future__ import annotations

import argparse

from hexaleg.commands.options import CYCLE_HELP
from hexaleg.errors import InvalidParameterError
from hexaleg.robot.registry import ROBOT_HELP


def add(sub: argparse._SubParsersAction) -> None:
    """Add ``motors`` to the subcommands."""
    p = sub.add_parser("motors", help="servo catalogue: gear ratio, torque constant, resistance, "
                                      "gearbox efficiency, Joule coefficient, datasheet")
    p.add_argument("names", nargs="*", help="motor names (default: the whole catalogue)")
    p.add_argument("--identify", metavar="LOG", help="fit the robot's actuators to a log of its "
                   "own gait with current_<joint> (A) and/or power_<joint> (W) columns, "
                   "optionally torque_<joint> (N·m): k_t G, gearbox efficiency and Joule "
                   "coefficient by least squares, with residuals and a [motor] table to use")
    p.add_argument("--robot", help=ROBOT_HELP + " (with --identify; default hexaleg)")
    p.add_argument("--config", help="with --identify: TOML file whose [motor] and [contact] "
                                    "tables describe the actuators as known before")
    p.add_argument("--cycle", default="auto",
                   help=CYCLE_HELP.replace("with --motion", "with --identify"))
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    """``hexaleg motors``: the catalogue, or the robot's actuators fitted to a log."""
    from hexaleg.robot.catalogue import CATALOGUE, catalogue_table, motor

    if args.identify is None:
        for flag in ("robot", "config"):
            if getattr(args, flag) is not None:
                raise InvalidParameterError(f"--{flag}", getattr(args, flag),
                                            "only with --identify LOG")
        if args.cycle != "auto":
            raise InvalidParameterError("--cycle", args.cycle, "only with --identify LOG")
        print(catalogue_table({n: motor(n) for n in args.names} if args.names else None))
        return 0
    if args.names:
        raise InvalidParameterError("names", " ".join(args.names), "none with --identify: the "
                                    "actuators are the robot's (its description, or [motor])")
    from hexaleg.commands.options import load_run
    from hexaleg.dynamics.identification import identify_motion
    from hexaleg.report.config import ReportConfig

    run = load_run(args.robot, args.config, args.identify, args.cycle, args)
    known = ReportConfig.from_scenario(run)
    fits = identify_motion(run.model, run.motion(), known.motor, contact=known.contact)
    for fit in fits.values():
        print("\n".join(fit.lines()))
    base = known.motor.name
    if len(fits) == 1 and base in CATALOGUE:  # the table that makes it every command's motor
        m = next(iter(fits.values())).identification.motor
        print(f"\n[motor]  # identified from {args.identify}\nbase = \"{base}\"\n"
              f"torque_constant = {m.torque_constant:.6g}\nresistance = {m.resistance:.6g}\n"
              f"gearbox_efficiency = {m.gearbox_efficiency:.6g}")
    else:
        print(f"\nno [motor] table printed: {base} is not one catalogue motor (a [motor] table "
              "with every field, or one per joint class in the robot's description: "
              "docs/energy.md)")
    return 0


__all__ = ["add", "run"]
