"""The ``hexaleg`` command line: the parser of every subcommand, and the entry point.

Each subcommand is its command's ``add(subparsers)``, which registers its options and its
``run(args)`` (:mod:`hexaleg.commands`: one package or module per command), listed in
:data:`SUBCOMMANDS`; :func:`main` runs the one asked for. Errors derived from
:class:`~hexaleg.errors.HexalegError` are printed as one line and exit with status 2; Ctrl-C,
SIGTERM and a closed pipe end in one line and the shell's status.
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
from hexaleg.commands import gait, motors, robot
from hexaleg.commands.codesign import command as codesign
from hexaleg.commands.design import command as design
from hexaleg.commands.paper import command as paper
from hexaleg.commands.parser import GUIDE, START, TEXT_OPTIONS, Parser, nonempty
from hexaleg.commands.report import command as report
from hexaleg.commands.simulate import command as simulate
from hexaleg.commands.sweep import command as sweep
from hexaleg.commands.view import command as view
from hexaleg.errors import HexalegError, HexalegWarning
from hexaleg.parallel import interrupt

SUBCOMMANDS = [robot.add, motors.add, gait.add, paper.add, report.add, design.add, view.add,
               sweep.add, simulate.add, codesign.add]
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
