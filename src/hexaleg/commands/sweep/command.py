"""The ``hexaleg sweep`` subcommand: its parser and its run (registered in
:data:`hexaleg.cli.SUBCOMMANDS`).

A spec file (docs/sweep.md) or the one-group flags (``--joints`` with ``--k``, ``--theta-k``,
``--dead-zone``, ``--offset`` or ``--family``); ``--motion LOG`` sweeps the log's cycle
(:mod:`hexaleg.sweep.logged`).
"""

from __future__ import annotations

import argparse
import dataclasses

from hexaleg.commands.options import add_motion_option, add_quiet
from hexaleg.errors import InvalidParameterError
from hexaleg.robot.registry import ROBOT_HELP
from hexaleg.sweep.optimal import OptimalSpec


def add(sub: argparse._SubParsersAction) -> None:
    """Add ``sweep`` to the subcommands."""
    p = sub.add_parser("sweep", help="spring stiffness / dead-zone / placement sweep over a grid, "
                                     "resumable, on a process pool or a Dask cluster")
    p.add_argument("spec", nargs="?", help="TOML sweep spec (see docs/sweep.md); or use the "
                                           "flags below for a one-group sweep")
    p.add_argument("--out", default="sweep-results",
                   help="output directory; rerun with the same spec to resume "
                        "(default: %(default)s)")
    p.add_argument("--executor", choices=("process", "serial", "dask"), default=None,
                   help="default: dask with --scheduler, else process")
    p.add_argument("--scheduler", help="Dask scheduler address, e.g. tcp://host:8786")
    p.add_argument("--workers", type=int, help="local process pool size (default: all cores)")
    p.add_argument("--robot", help=ROBOT_HELP + " (with a spec file: its [sweep] robot)")
    p.add_argument("--joints", help="one-group sweep: joint class (coxa, femur, tibia) or joint")
    for flag, what in (("--k", "stiffness, N·m/rad"), ("--theta-k", "contact angle θ_k, rad"),
                       ("--dead-zone", "θ_k as a fraction of the half range of motion"),
                       ("--offset", "neutral offset from the centre of motion, rad")):
        p.add_argument(flag, help=f"{what}: VALUE, V1,V2,… or START:STOP:NUM[:log]")
    p.add_argument("--family", help="instead of a grid of designs: the globally optimal spring "
                                    "of this family on --joints at each gait (linear, dead_zone, "
                                    "preloaded, one_sided, stiffening)")
    p.add_argument("--max-torque", type=float, help="with --family: largest spring torque, N·m")
    p.add_argument("--max-deflection", type=float,
                   help="with --family: largest spring deflection from its free position, rad")
    p.add_argument("--period", help="gait period, s (values as above)")
    p.add_argument("--samples", type=int, help="samples per gait cycle")
    p.add_argument("--metric", help="metric to rank by (default: electrical)")
    add_quiet(p)
    add_motion_option(p, run, None)


def run(args: argparse.Namespace) -> int:
    """Run ``hexaleg sweep`` with the parsed ``args``; 0 on success."""
    from hexaleg.sweep import SweepSpec, run_sweep, summary

    values = {"k": args.k, "theta_k": args.theta_k, "dead_zone": args.dead_zone,
              "offset": args.offset}
    design = (args.family, args.max_torque, args.max_deflection)
    if args.spec and (args.joints or any(v is not None for v in (*values.values(), *design))):
        raise InvalidParameterError("--joints/--k/--theta-k/--dead-zone/--offset/--family",
                                    "given with a spec file", "either a spec or the flags")
    if args.spec and args.robot:
        raise InvalidParameterError("--robot", args.robot, "the spec file's [sweep] robot = "
                                    "… with a spec file")
    if args.family is None and (args.max_torque, args.max_deflection) != (None, None):
        raise InvalidParameterError("--max-torque/--max-deflection", "given without --family",
                                    "bounds of the optimal design of --family")
    optimal = (OptimalSpec(family=(args.family,), max_torque=args.max_torque,
                           max_deflection=args.max_deflection) if args.family else None)
    spec = (SweepSpec.from_toml(args.spec) if args.spec else
            SweepSpec.one_group(args.joints, values, period=args.period, samples=args.samples,
                                optimal=optimal, robot=args.robot or "hexaleg"))
    if args.metric:
        spec = dataclasses.replace(spec, metric=args.metric)
    if args.motion:
        from hexaleg.commands.options import load_run
        from hexaleg.sweep.logged import on_log

        spec = on_log(spec, args.motion, args.cycle)  # refuses the gait keys a log replaces
        load_run(spec.run.robot, None, args.motion, args.cycle, args)  # the log's quality
    executor = args.executor or ("dask" if args.scheduler else "process")
    result = run_sweep(spec, args.out, executor=executor, workers=args.workers,
                       scheduler=args.scheduler, progress=not args.quiet)
    print(summary(result.table, spec.metric))
    print(f"{result.computed} points computed, {result.reused} reused; results in "
          f"{result.directory} (part-*.parquet, one table: pandas.read_parquet(DIR))")
    if not (result.table["status"] == "ok").any():
        raise InvalidParameterError("sweep", f"{len(result.table)} points, none evaluated",
                                    "a grid with at least one point the robot can walk (the "
                                    "summary above gives each point's error)")
    return 0


__all__ = ["add", "run"]
