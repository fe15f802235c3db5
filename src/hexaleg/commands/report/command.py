"""The ``hexaleg report`` subcommand: its parser and its run (registered in
:data:`hexaleg.cli.SUBCOMMANDS`): the run loaded, the report written
(:func:`hexaleg.commands.report.write.write_report`), its notes, warnings and answer printed.
"""

from __future__ import annotations

import argparse

from hexaleg.commands.options import add_motion_option, add_quiet, print_warnings
from hexaleg.robot.registry import ROBOT_HELP  # loaded by `import hexaleg` already


def add(sub: argparse._SubParsersAction) -> None:
    """Add ``report`` to the subcommands."""
    p = sub.add_parser("report", help="gait energy report: report.html (self-contained), "
                                      "report.json and the plots, with and without springs")
    p.add_argument("--config", help="TOML file with optional [gait], [motor], [contact], "
                                    "[springs], [report] and [payload] tables (see "
                                    "docs/report.md, docs/gaits.md)")
    p.add_argument("--out", default="hexaleg-report",
                   help="output directory (default: %(default)s)")
    p.add_argument("--svg", action="store_true", help="also write every plot as SVG")
    p.add_argument("--robot", help=ROBOT_HELP + ": its gait (keys [gait] does not set), "
                                                "springs and curve on its spring class")
    p.add_argument("--design", help="a design.json of 'hexaleg design' to lead the page with")
    add_quiet(p)
    add_motion_option(p, run, "report.json")


def run(args: argparse.Namespace) -> int:
    """Write the report; print its notes, the run's warnings and its summary, the answer last."""
    from hexaleg.commands.options import load_run, progress_of
    from hexaleg.commands.report.write import write_report
    from hexaleg.report.config import ReportConfig

    run = load_run(args.robot, args.config, args.motion, args.cycle, args)
    config, robot = ReportConfig.from_scenario(run), run.model
    if args.design:
        import dataclasses

        config = dataclasses.replace(config, report=dataclasses.replace(config.report,
                                                                        design=args.design))
    r = write_report(args.out, config, robot=robot, svg=args.svg,
                     progress=progress_of(args, "report"))
    for note in config.notes:
        print(f"note: {note}")
    print_warnings(r.data["warnings"])
    print(f"wrote {len(r.files)} files to {args.out}; open {args.out}/report.html")
    print(r.summary())  # its last line is the answer: which springs, and what they save
    return 0


__all__ = ["add", "run"]
