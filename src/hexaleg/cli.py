"""The ``hexaleg`` command line: thin subcommands over the public API.

Each subcommand is a pair ``_add_<name>(subparsers)`` / ``_run_<name>(args)``; errors derived
from :class:`~hexaleg.errors.HexalegError` are printed as one line and exit with status 2.
"""

from __future__ import annotations

import argparse
import functools
import os
import re
import sys
import textwrap
import warnings
from collections.abc import Callable, Sequence
from typing import NoReturn, TextIO

from hexaleg import __version__
from hexaleg.commands.options import (  # no loader: it loads with a run
    CYCLE_HELP,
    add_motion_option,
)
from hexaleg.errors import HexalegError, HexalegWarning, InvalidParameterError, did_you_mean
from hexaleg.robot.registry import ROBOT_HELP  # loaded by `import hexaleg` already
from hexaleg.simulation.controllers import CONTROLLERS  # no MuJoCo: it loads with a model


def _add_robot(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("robot", help="summary of the loaded robot model: links, masses, joints, "
                                     "limits, legs, poses")
    p.add_argument("--urdf", help="URDF file (default: the built-in hexaleg robot)")
    p.add_argument("--srdf", help="SRDF file with poses and disabled collision pairs")
    p.add_argument("--robot", help=ROBOT_HELP + " instead of --urdf/--srdf")
    p.set_defaults(func=_run_robot)


def _run_robot(args: argparse.Namespace) -> int:
    from hexaleg.errors import InvalidParameterError
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


def _add_motors(sub: argparse._SubParsersAction) -> None:
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
    p.set_defaults(func=_run_motors)


def _run_motors(args: argparse.Namespace) -> int:
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
    fits = identify_motion(run.model, run.played(), known.motor, contact=known.contact)
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
    p.set_defaults(func=_run_paper)


def _run_paper(args: argparse.Namespace) -> int:
    from hexaleg.commands.paper.command import run_paper

    return run_paper(args.out, n=args.samples, simulation=args.simulation, grid=args.grid)


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
    motion = run.played()
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
    add_motion_option(p, _run_report, "report.json")


def _run_report(args: argparse.Namespace) -> int:
    from hexaleg.commands.options import load_run
    from hexaleg.commands.report.write import write_report
    from hexaleg.report.config import ReportConfig

    run = load_run(args.robot, args.config, args.motion, args.cycle, args)
    config, robot = ReportConfig.from_scenario(run), run.model
    if args.design:
        import dataclasses

        config = dataclasses.replace(config, report=dataclasses.replace(config.report,
                                                                        design=args.design))
    r = write_report(args.out, config, robot=robot, svg=args.svg)
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
    p.add_argument("--controller", choices=CONTROLLERS,
                   help="the servo the robot runs, which the designs are simulated and ranked "
                        "under (default: the config's [design] controller, else feedforward)")
    p.add_argument("--out", default="hexaleg-design",
                   help="output directory (default: %(default)s)")
    add_motion_option(p, _run_design, "design.json")


def _run_design(args: argparse.Namespace) -> int:
    from hexaleg.commands.design.write import write_design
    from hexaleg.commands.options import load_run
    from hexaleg.design.chain.config import DesignConfig

    run = load_run(args.robot, args.config, args.motion, args.cycle, args)
    config = DesignConfig.from_scenario(run, args.controller)
    written = write_design(args.out, config)
    _warn_lines(written.data["warnings"])
    print(written.result.summary())
    if written.result.whole_draw is not None:
        print(written.result.whole_draw.line())
    print(f"wrote {len(written.files)} files to {args.out}; open {args.out}/design.html")
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
    from hexaleg.simulation.motion_file import write_motions

    overrides = {"controller": args.controller, "cycles": args.cycles,
                 "timestep": args.timestep}
    if args.cycles is not None and args.cycles >= 2:
        overrides["evaluate"] = min(2, args.cycles - 1)
    run = load_run(args.robot, args.config, args.motion, args.cycle, args)
    study = load_study(run, args.springs, overrides)
    s = study.run()
    rows = None
    if args.sensitivity and s.walks:
        from hexaleg.simulation.sensitivity import sensitivity

        rows = sensitivity(s)
    data = simulation_data(s, design=study.design, notes=study.notes, sensitivity=rows,
                           warnings=study.warnings, gait_defaults=study.gait_defaults)
    js, md, html = write_simulation(args.out, data)
    motions = ", ".join(str(m) for m in write_motions(args.out, s))
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


SUBCOMMANDS = [_add_robot, _add_motors, _add_gait, _add_paper, _add_report, _add_design,
               _add_view, __import__("hexaleg.commands.sweep.command", fromlist=["add"]).add,
               _add_simulate,
               __import__("hexaleg.commands.codesign.command", fromlist=["add"]).add]
"""Parser builders, one per subcommand, in the order ``--help`` lists them."""


class _Parser(argparse.ArgumentParser):
    """argparse's parser whose usage errors suggest the command or option meant (``hexaleg
    desing`` → ``design``; ``--robt`` → ``--robot``)."""

    def error(self, message: str) -> NoReturn:
        choice = re.search(r"invalid choice: '([^']*)' \(choose from (.*)\)", message)
        if choice:
            message += did_you_mean(choice.group(1), re.findall(r"'([^']*)'", choice.group(2)))
        unknown = re.search(r"unrecognized arguments: (-[-\w]*)", message)
        if unknown:
            options = [o for a in self._all_actions() for o in a.option_strings]
            message += did_you_mean(unknown.group(1), options)
        super().error(message)

    def _all_actions(self) -> list[argparse.Action]:
        """This parser's actions and those of the subcommand parsers below it."""
        out = list(self._actions)
        for action in self._actions:
            if isinstance(action.choices, dict):
                for sub in action.choices.values():
                    out += sub._actions
        return out


GUIDE: dict[str, tuple[str, tuple[str, ...]]] = {
    "robot": ("under a second", ("hexaleg robot", "hexaleg robot --robot my_robot.toml")),
    "motors": ("under a second; --identify a few seconds", (
        "hexaleg motors", "hexaleg motors AX-18A XM430-W350",
        "hexaleg motors --identify walk.csv")),
    "gait": ("about 2 s", ("hexaleg gait", "hexaleg gait --robot solo12")),
    "paper": ("about 7 s", ("hexaleg paper", "hexaleg paper --out paper-results")),
    "report": ("about 5 s", ("hexaleg report", "hexaleg report --design "
                                               "hexaleg-design/design.json")),
    "design": ("about 20 s on the built-in robot, minutes on a heavy quadruped",
               ("hexaleg design", "hexaleg design --controller position --out my-design")),
    "view": ("about 2 s to draw", ("hexaleg view", "hexaleg view --html walk.html",
                                   "hexaleg view --simulation hexaleg-simulate")),
    "sweep": ("about 2 s for a 40-point grid", ("hexaleg sweep --joints femur --k 0:0.05:41 "
                                                "--dead-zone 0.4", "hexaleg sweep spec.toml")),
    "simulate": ("about 3 s", ("hexaleg simulate", "hexaleg simulate --springs "
                                                   "hexaleg-design/design.json --controller "
                                                   "position")),
    "codesign": ("about 5 minutes", ("hexaleg codesign",
                                                           "hexaleg codesign --speed 0.1")),
}
"""Per command: how long it takes on the built-in robot (measured on two cores, nothing else
running) and examples. ``--help`` shows both; the README's command table quotes the times
(``tests/test_readme.py``)."""
START = """start with:
  hexaleg report      which springs to fit, and the gait's energy with them (about 5 s)
  hexaleg design      the full answer: every spring family, the springs to buy (about 20 s)
  hexaleg simulate    the report's answer checked in a MuJoCo simulation (about 3 s)
  hexaleg view        the gait in the browser, foot forces and joint colours

each command: hexaleg COMMAND --help (what it writes, how long it takes, examples);
the documentation is docs/ in the source repository"""
"""The top-level ``--help``'s closing lines: where a newcomer starts."""


TEXT_OPTIONS = ("out", "config", "robot", "design", "springs", "html", "identify", "host",
                "simulation", "motion", "scheduler", "spec", "urdf", "srdf", "cycle", "pattern")
"""The options that take a name or a path: each refuses an empty value (``--out ""`` once
wrote into the working directory, ``--html ""`` served instead of writing, ``--host ""``
listened on every interface)."""


def _nonempty(text: str) -> str:
    """An option's value when it is not empty (:data:`TEXT_OPTIONS`)."""
    if not text.strip():
        raise argparse.ArgumentTypeError("an empty value; give a name or a path, or leave the "
                                         "option out for its default")
    return text


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
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
                a.type = _nonempty
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


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``hexaleg`` console script.

    Returns:
        Exit status: 0 on success, 2 on a hexaleg error (message on stderr), 141 when the
        reader of standard output went away early (``hexaleg robot | head``), as a tool killed
        by SIGPIPE would report, without a traceback.
    """
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
        with warnings.catch_warnings():
            warnings.showwarning = functools.partial(_show_warning, args.command,
                                                     warnings.showwarning)
            status = int(args.func(args) or 0)
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


if __name__ == "__main__":
    sys.exit(main())
