"""The ``hexaleg design`` subcommand: its parser and its run (registered in
:data:`hexaleg.cli.SUBCOMMANDS`): the run loaded, the design written
(:func:`hexaleg.commands.design.write.write_design`), its answer line printed; a failed stage
is one line on stderr and status 2, the stages before it written.
"""

from __future__ import annotations

import argparse
import sys

from hexaleg.commands.options import add_motion_option, add_quiet, print_warnings
from hexaleg.robot.registry import ROBOT_HELP  # loaded by `import hexaleg` already
from hexaleg.simulation.controllers import SERVOS  # no MuJoCo: it loads with a model


def add(sub: argparse._SubParsersAction) -> None:
    """Add ``design`` to the subcommands."""
    p = sub.add_parser("design", help="which springs to fit: the globally optimal design per "
                                      "family ranked by the energy the servos draw, torsion "
                                      "springs to buy, robustness maps, the robust design: "
                                      "design.html, design.json")
    p.add_argument("--robot", default="hexaleg", help=ROBOT_HELP + " (default %(default)s)")
    p.add_argument("--config", help="TOML file with optional [gait], [contact] and [design] "
                                    "tables (docs/design.md)")
    p.add_argument("--controller", choices=SERVOS,
                   help="the servo the robot runs, which the designs are simulated and ranked "
                        "under; both: each, ranked by the worse (default: the config's [design] "
                        "controller, else both)")
    p.add_argument("--out", default="hexaleg-design",
                   help="output directory (default: %(default)s)")
    add_quiet(p)
    add_motion_option(p, run, "design.json")


def run(args: argparse.Namespace) -> int:
    """Run the design and write its files; print its answer line (status 2 on a failed stage)."""
    from hexaleg.commands.design.write import write_design
    from hexaleg.commands.options import load_run, progress_of

    run = load_run(args.robot, args.config, args.motion, args.cycle, args)
    written = write_design(args.out, run, controller=args.controller,
                           progress=progress_of(args, "design"))
    print_warnings(written.data["warnings"])
    print(written.result.summary())
    if written.result.whole_draw is not None:
        print(written.result.whole_draw.line())
    if written.result.fold is not None:
        print(written.result.fold.line())
    print(f"wrote {len(written.files)} files to {args.out}; open {args.out}/design.html")
    failed = written.result.failed
    if failed is not None:  # the stages before it are written: one line, a failed status
        print(f"hexaleg design: error: {failed.line()}; the same command resumes from the "
              f"stages kept in {args.out}", file=sys.stderr)
        return 2
    return 0


__all__ = ["add", "run"]
