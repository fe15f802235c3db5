"""The ``hexaleg`` command line: thin subcommands over the public API.

Each subcommand is a pair ``_add_<name>(subparsers)`` / ``_run_<name>(args)``; errors derived
from :class:`~hexaleg.errors.HexalegError` are printed as one line and exit with status 2.
"""

from __future__ import annotations

import argparse
import codecs
import functools
import io
import os
import signal
import sys
import textwrap
import warnings
from collections.abc import Callable, Sequence
from typing import TextIO

from hexaleg import __version__
from hexaleg.commands.options import add_motion_option, add_quiet  # no loader: loads with a run
from hexaleg.commands.parser import GUIDE, START, TEXT_OPTIONS, Parser, nonempty
from hexaleg.errors import HexalegError, HexalegWarning, InvalidParameterError
from hexaleg.parallel import interrupt
from hexaleg.robot.registry import ROBOT_HELP  # loaded by `import hexaleg` already
from hexaleg.simulation.balance import MODES as FEEDBACK  # no MuJoCo: it loads with a model
from hexaleg.simulation.controllers import CONTROLLERS, SERVOS  # no MuJoCo either


def _add_robot(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("robot", help="summary of the loaded robot model: links, masses, joints, "
                                     "limits, legs, poses")
    p.add_argument("--urdf", help="URDF file (default: the built-in hexaleg robot)")
    p.add_argument("--srdf", help="SRDF file with poses and disabled collision pairs")
    p.add_argument("--robot", help=ROBOT_HELP + " instead of --urdf/--srdf")
    p.set_defaults(func=_run_robot)


def _run_robot(args: argparse.Namespace) -> int:
    from hexaleg.robot.model import load_robot
    from hexaleg.robot.registry import load
    from hexaleg.robot.sanity import robot_findings

    if args.robot is not None and (args.urdf or args.srdf):
        raise InvalidParameterError("--robot", args.robot, "either --robot or --urdf/--srdf")
    robot = load(args.robot) if args.robot is not None else load_robot(args.urdf, args.srdf)
    print(robot.summary())
    _warn(robot_findings(robot))
    return 0


def _warn(findings: list) -> None:
    """Print the sanity checks' findings (:mod:`hexaleg.robot.sanity`) as warnings."""
    _warn_lines([finding.message for finding in findings])


def _warn_lines(lines: Sequence[str]) -> None:
    """Print a run's warnings (:meth:`hexaleg.scenario.scenario.Scenario.warnings`), one
    ``warning:`` line each."""
    for line in lines:
        print(f"warning: {line}")


def _add_paper(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("paper", help="reproduce the paper's single elastic joint: paper.json, "
                                     "Fig. 5-13 analogues (PNG), summary.md, and its Adams "
                                     "experiment forward in MuJoCo beside them")
    p.add_argument("--out", default="hexaleg-paper", help="output directory (default: %(default)s)")
    p.add_argument("--samples", type=int, default=8192,
                   help="samples per trajectory period (default: %(default)s)")
    # hexaleg.paper.forward.K_GRID, which is not imported to build the parser
    p.add_argument("--grid", type=float, nargs="+", metavar="K",
                   help="stiffnesses of the forward run, the paper's eq. 19 units (1e-6 N·m/rad), "
                        "at least 3, increasing (default: 100 to 1600 in steps of 100)")
    p.add_argument("--no-simulation", dest="simulation", action="store_false",
                   help="leave out the forward run (the analytic reproduction only)")
    add_quiet(p)
    p.set_defaults(func=_run_paper)


def _run_paper(args: argparse.Namespace) -> int:
    from hexaleg.commands.options import progress_of
    from hexaleg.commands.paper.command import run_paper

    return run_paper(args.out, n=args.samples, simulation=args.simulation, grid=args.grid,
                     progress=progress_of(args, "paper"))


def _add_gait(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("gait", help="the tripod gait: parameters, static margin, joint ranges, "
                                    "peak joint speeds and accelerations")
    p.add_argument("--config", help="TOML file with a [gait] table; its keys replace those of "
                                    "the robot's gait (its description's, the keys it leaves "
                                    "unset sized to it: docs/robots.md)")
    p.add_argument("--robot", default="hexaleg", help=ROBOT_HELP + " (default %(default)s)")
    p.set_defaults(func=_run_gait)


def _run_gait(args: argparse.Namespace) -> int:
    from hexaleg.commands.options import load_run
    from hexaleg.motion.sanity import motion_findings
    from hexaleg.outputs.text import gait_summary
    from hexaleg.robot.sanity import robot_findings

    run = load_run(args.robot, args.config)
    motion = run.motion()
    print(gait_summary(run.model, motion))
    warned = run.warnings(motion)
    _warn_lines(warned)  # the same lines as report, design and simulate say for this run
    _warn([f for f in (*robot_findings(run.model), *motion_findings(run.model, motion))
           if f.message not in warned])
    return 0


def _add_view(sub: argparse._SubParsersAction) -> None:
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
    # The names of hexaleg.commands.view's MOTIONS, JOINT_QUANTITIES and motion_file.RUNS, which
    # check them too (the study is not imported to build the parser: meshcat imports slowly).
    p.add_argument("--simulation", metavar="DIR", help="replay a run of 'hexaleg simulate "
                                                       "--out DIR' instead (its motion files)")
    p.add_argument("--run", choices=("springs", "baseline"), help="with --simulation: the run "
                   "with the springs or without (default: springs)")
    p.add_argument("--joints", choices=("power", "torque", "spring"), default="power",
                   help="what colours the joints: motor power (W), motor torque or spring "
                        "torque (N·m) (default: %(default)s)")
    add_motion_option(p, _run_view, None, ("gait", "transform"),
                      "gait (the tripod gait cycle, default), transform (stand → sphere) or a "
                      "log FILE of the robot's own gait (docs/motion.md)")


def _run_view(args: argparse.Namespace) -> int:
    from hexaleg.commands.view import export_view, serve_view, wait_until_interrupted

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


def _add_report(sub: argparse._SubParsersAction) -> None:
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
    add_motion_option(p, _run_report, "report.json")


def _run_report(args: argparse.Namespace) -> int:
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
    _warn_lines(r.data["warnings"])
    print(f"wrote {len(r.files)} files to {args.out}; open {args.out}/report.html")
    print(r.summary())  # its last line is the answer: which springs, and what they save
    return 0


def _add_design(sub: argparse._SubParsersAction) -> None:
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
    add_motion_option(p, _run_design, "design.json")


def _run_design(args: argparse.Namespace) -> int:
    from hexaleg.commands.design.write import write_design
    from hexaleg.commands.options import load_run, progress_of

    run = load_run(args.robot, args.config, args.motion, args.cycle, args)
    written = write_design(args.out, run, controller=args.controller,
                           progress=progress_of(args, "design"))
    _warn_lines(written.data["warnings"])
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


def _add_simulate(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("simulate", help="forward simulation in MuJoCo with and without the "
                                        "springs: simulate.html, .json and .md, predicted vs "
                                        "simulated energy and saving, the motion of each run")
    p.add_argument("--robot", default="hexaleg", help=ROBOT_HELP + " (default %(default)s)")
    p.add_argument("--config", help="TOML file with optional [gait], [motor], [contact] and "
                                    "[simulate] tables (docs/simulate.md)")
    p.add_argument("--springs", help="design file (design.json: springs per joint as family and "
                                     "parameters, docs/simulate.md); default: the springs "
                                     "hexaleg report leads with (its answer)")
    p.add_argument("--controller", choices=CONTROLLERS,
                   help="servo: torque feedforward + PD, or position-only PD "
                        "(default: feedforward, or the config's)")
    p.add_argument("--feedback", choices=FEEDBACK,
                   help="balance feedback on the body: auto (where the gait stands on fewer "
                        "than three feet or open loop falls), on, off (open loop) (default: "
                        "auto, or the config's)")
    p.add_argument("--cycles", type=int, help="gait cycles simulated (default 4, the last 2 "
                                              "evaluated)")
    p.add_argument("--timestep", type=float, help="simulation timestep, s (default: 0.5 ms, "
                                                  "or less for a fine gait or stiff servos)")
    p.add_argument("--sensitivity", action="store_true",
                   help="also rerun with the servo gains ×0.25…×4, the ground 4× softer and "
                        "stiffer, half the friction, the no-slip pass and the other controller")
    p.add_argument("--out", default="hexaleg-simulate",
                   help="output directory (default: %(default)s)")
    add_motion_option(p, _run_simulate, "simulate.json")


def _run_simulate(args: argparse.Namespace) -> int:
    from hexaleg.commands.options import load_run
    from hexaleg.commands.simulate.study import load_study
    from hexaleg.commands.simulate.write import simulation_data, summary, write_simulation
    from hexaleg.errors import SimulationError
    from hexaleg.outputs.directory import OutputFolder
    from hexaleg.simulation.motion_file import write_motions

    overrides = {"controller": args.controller, "feedback": args.feedback,
                 "cycles": args.cycles, "timestep": args.timestep}
    if args.cycles is not None and args.cycles >= 2:
        overrides["evaluate"] = min(2, args.cycles - 1)
    run = load_run(args.robot, args.config, args.motion, args.cycle, args)
    study = load_study(run, args.springs, overrides)
    with OutputFolder(args.out, "simulation") as folder:  # locked; published whole at the end
        s = study.run()
        rows = None
        if args.sensitivity and s.walks:
            from hexaleg.simulation.sensitivity import sensitivity

            rows = sensitivity(s)
        data = simulation_data(s, design=study.design, notes=study.notes, sensitivity=rows,
                               warnings=study.warnings, gait_defaults=study.gait_defaults)
        js, md, html = (folder.directory / p.name
                        for p in write_simulation(folder.staging, data))
        motions = ", ".join(str(folder.directory / m.name)
                            for m in write_motions(folder.staging, s))
        folder.publish()
    for note in study.notes:
        print(f"note: {note}")
    _warn_lines(study.warnings)
    print(summary(data))
    print(f"wrote {js}, {md}, {motions}; open {html} (replay: hexaleg view --simulation "
          f"{args.out})")
    if not s.walks:
        raise SimulationError("; ".join(f"{r.name} run {r.verdict}: {r.message}"
                                        for r in (s.with_springs, s.baseline) if not r.walks))
    return 0


SUBCOMMANDS = [_add_robot, __import__("hexaleg.commands.motors", fromlist=["add"]).add,
               _add_gait, _add_paper, _add_report, _add_design,
               _add_view, __import__("hexaleg.commands.sweep.command", fromlist=["add"]).add,
               _add_simulate,
               __import__("hexaleg.commands.codesign.command", fromlist=["add"]).add]
"""Parser builders, one per subcommand, in the order ``--help`` lists them."""


def build_parser() -> argparse.ArgumentParser:
    parser = Parser(
        prog="hexaleg",
        description="Whole-robot dynamics and energy analysis of legged robots with nonlinear "
                    "elastic joints.", epilog=START,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--version", action="version", version=f"hexaleg {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for add in SUBCOMMANDS:
        add(sub)
    for p in sub.choices.values():  # an empty name or path is an error, not the default
        for a in p._actions:
            if a.dest in TEXT_OPTIONS and a.type is None:
                a.type = nonempty
    for action in sub._choices_actions:  # each command's --help: what, how long, examples
        time, examples = GUIDE[action.dest]
        p = sub.choices[action.dest]
        p.description = textwrap.fill(f"{action.help}.", 79)
        p.epilog = (f"takes {time}.\n\nexamples:\n"
                    + "\n".join(f"  {e}" for e in examples))
        p.formatter_class = argparse.RawDescriptionHelpFormatter
    return parser


def _subparser(parser: argparse.ArgumentParser, command: str) -> argparse.ArgumentParser:
    """The parser of one subcommand."""
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            return action.choices[command]
    raise KeyError(command)


def _show_warning(command: str, original: Callable[..., None], message: Warning | str,
                  category: type[Warning], filename: str, lineno: int, file: TextIO | None = None,
                  line: str | None = None) -> None:
    """Print a :class:`~hexaleg.errors.HexalegWarning` as one line, others as Python does."""
    if issubclass(category, HexalegWarning):
        print(f"hexaleg {command}: warning: {message}", file=sys.stderr)
    else:
        original(message, category, filename, lineno, file, line)


def _spell_in_ascii_where_needed() -> None:
    """Standard output and error spell in ASCII what their encoding cannot show
    (:func:`hexaleg.units.ascii_spelling`: ``N·m`` → ``N*m`` under ``PYTHONIOENCODING=ascii``
    or a C locale), instead of failing on the first symbol."""
    from hexaleg.units import ascii_spelling

    codecs.register_error("hexaleg-ascii", ascii_spelling)
    for stream in (sys.stdout, sys.stderr):
        if isinstance(stream, io.TextIOWrapper) and stream.errors == "strict":
            stream.reconfigure(errors="hexaleg-ascii")


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``hexaleg`` console script.

    Returns:
        Exit status: 0 on success, 2 on a hexaleg error (message on stderr), 141 when the
        reader of standard output went away early (``hexaleg robot | head``), as a tool killed
        by SIGPIPE would report, without a traceback; 130 on Ctrl-C (SIGINT) and 143 on
        SIGTERM, after one line on stderr saying what was kept (every output directory as it
        was: :class:`hexaleg.outputs.directory.OutputFolder`).
    """
    _spell_in_ascii_where_needed()
    # no command renders with MuJoCo: without this its import loads GLFW and runs a subprocess
    # for the library's version (65-90 ms of every command that simulates); a user's own
    # MUJOCO_GL is kept
    os.environ.setdefault("MUJOCO_GL", "disable")
    parser = build_parser()
    args, extra = parser.parse_known_args(argv)
    if extra:  # named by the command's own parser: its usage, its options to suggest
        command = getattr(args, "command", None)
        own = parser if command is None else _subparser(parser, command)
        own.error(f"unrecognized arguments: {' '.join(extra)}")
    if not getattr(args, "func", None):
        parser.print_help()
        return 0
    try:
        # the view takes Ctrl-C even where it started ignored: it serves until interrupted
        with warnings.catch_warnings(), interrupt.handled(sigint=args.command == "view" or None):
            warnings.showwarning = functools.partial(_show_warning, args.command,
                                                     warnings.showwarning)
            status = int(args.func(args) or 0)
            interrupt.check()  # one lost on the way (raised in a __del__) is still reported
            sys.stdout.flush()  # a closed pipe fails here, inside the handler, not at shutdown
        return status
    except HexalegError as e:
        print(f"hexaleg {args.command}: error: {e}", file=sys.stderr)
        return 2
    except BrokenPipeError:
        # Point stdout at /dev/null so the interpreter's final flush does not fail again.
        # Recipe from the Python docs, "Note on SIGPIPE" in the signal module.
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return 128 + 13  # 128 + SIGPIPE, what a shell reports for `cat big | head`
    except KeyboardInterrupt as e:  # SIGINT, or SIGTERM (interrupt.Interrupted)
        return _interrupted(args.command, e)
    except Exception as e:  # an interrupt inside an import is an ImportError raised from it
        cause = interrupt.found(e)
        if cause is None:
            raise
        return _interrupted(args.command, cause)


def _interrupted(command: str, e: KeyboardInterrupt) -> int:
    """One line for an interrupted command, saying what it kept; the exit status."""
    signum = getattr(e, "signum", signal.SIGINT)
    kept = "; ".join(interrupt.kept(e)) or "nothing written"
    print(f"hexaleg {command}: interrupted ({signal.Signals(signum).name}): {kept}",
          file=sys.stderr)
    return 128 + signum  # what a shell reports for a process ended by the signal


if __name__ == "__main__":
    sys.exit(main())
