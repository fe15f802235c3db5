"""What every command shares: ``--motion``/``--cycle``, and the one loader of a run.

:func:`load_run` builds a command's :class:`~hexaleg.scenario.scenario.Scenario` from
``--robot``, ``--config``, ``--motion`` and ``--cycle`` and checks *every* table of the file
with its owner (:func:`check_tables`), whichever command runs: a bad ``[gait]``, ``[design]``
or ``[codesign]`` value is the same named error in ``hexaleg gait``, ``report``, ``design``,
``simulate``, ``codesign`` and ``view``.

:func:`add_quiet` adds ``--quiet`` to a command whose work takes seconds or more, and
:func:`progress_of` is its one printer of status lines (``hexaleg <command>: …`` on stderr).

:func:`add_motion_option` adds ``--motion FILE`` and ``--cycle`` to a subcommand; after the
command ran with a log, the log's quality figures are printed and written to the command's JSON
file as ``motion_quality`` (:func:`hexaleg.scenario.logged.quality_data`). The parser imports
this module, so the loaders are imported only when a run is loaded.

:func:`print_warnings` prints a run's warnings, :func:`print_findings` the sanity checks'
findings: one ``warning:`` line each, the same in every command.
"""

from __future__ import annotations

import argparse
import functools
import sys
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from hexaleg.errors import InvalidParameterError

if TYPE_CHECKING:
    from hexaleg.scenario.scenario import Scenario

MOTION_HELP = ("a log of the robot's own gait (CSV with a header row or NPZ: time, joint angles, "
               "optional base pose and contact_<LEG>; or a ROS 2 bag directory; docs/motion.md) "
               "instead of the generated gait")
"""What ``--motion`` takes."""
CYCLE_HELP = ("with --motion: 'auto' (the period found and the log's cycles averaged into one "
              "periodic cycle), 'whole' (the log is exactly one cycle, taken as periodic) or "
              "T0:T1 (one cycle's window, s from the first stamp) (default: %(default)s)")
"""What ``--cycle`` takes."""


def load_run(robot: str | None, config: str | Path | None, motion: str | Path | None = None,
             cycle: str = "auto", args: argparse.Namespace | None = None) -> Scenario:
    """The run of a command (module docstring), every table of ``config`` checked first.

    Args:
        robot: ``--robot`` (None: the built-in robot).
        config: ``--config``, or None.
        motion: ``--motion`` (a log), or None.
        cycle: ``--cycle``.
        args: The command's parsed options: the run is kept on them (``args.scenario``) for
            :func:`add_motion_option`'s quality lines.

    Raises:
        ConfigError, UnknownNameError, InvalidParameterError: a bad file, table, key or value
            (named, with what is allowed), before the robot or the log is read.
    """
    from hexaleg.config import load_toml
    from hexaleg.scenario.scenario import Scenario

    tables = load_toml(config) if config else {}
    where = str(config) if config else "config"
    check_tables(tables, where, motion)
    scenario = Scenario.from_tables(robot or "hexaleg", tables, where, log=motion, cycle=cycle)
    if args is not None:
        args.scenario = scenario
    return scenario


def check_tables(tables: Mapping[str, Any], where: str, log: str | Path | None = None) -> None:
    """Check every table of a config document with its owner, whichever command reads it: the
    table names (:data:`hexaleg.scenario.scenario.TABLES`), ``[gait]`` and ``[contact]``
    refused with a log (:func:`hexaleg.scenario.logged.refuse_gait_table`), ``[design]``
    (:class:`~hexaleg.design.chain.config.DesignParams`; no ``samples`` with a log),
    ``[mission]`` (:class:`~hexaleg.design.fold.Mission`),
    ``[codesign]`` (:func:`~hexaleg.design.codesign.build.codesign_settings`), ``[simulate]``
    (:class:`~hexaleg.simulation.run.Settings`), ``[report]``, ``[springs]`` and ``[payload]``
    (:class:`~hexaleg.report.config.ReportConfig`), ``[view]``
    (:class:`~hexaleg.outputs.viewer.show.ViewParams`). The run's own ``[gait]``, ``[contact]``
    and ``[motor]`` are checked once, by their owner
    (:meth:`~hexaleg.scenario.scenario.Scenario.from_tables`, before the robot is loaded).

    Raises:
        ConfigError, UnknownNameError, InvalidParameterError: the first bad value (named).
    """
    from hexaleg.config import check_tables as check_names
    from hexaleg.config import from_mapping
    from hexaleg.design.chain.config import DesignParams
    from hexaleg.design.codesign.build import codesign_settings
    from hexaleg.design.fold import Mission
    from hexaleg.outputs.viewer.show import ViewParams
    from hexaleg.report.config import ReportConfig
    from hexaleg.scenario.logged import refuse_gait_table
    from hexaleg.scenario.scenario import TABLES
    from hexaleg.simulation.settings import Settings

    check_names(tables, tuple(TABLES), where)
    if log is not None:
        refuse_gait_table(tables, where, log)
    design = tables.get("design", {})
    if log is not None and isinstance(design, Mapping) and "samples" in design:
        raise InvalidParameterError(
            f"{where} [design] samples", design["samples"],
            f"no samples with --motion {log}: the logged cycle keeps its own samples; remove the "
            "key or the --motion option")
    from_mapping(DesignParams, design, f"{where} [design]")
    from_mapping(Mission, tables.get("mission", {}), f"{where} [mission]")
    codesign_settings(tables.get("codesign", {}), f"{where} [codesign]")
    Settings.from_mapping(tables.get("simulate", {}), f"{where} [simulate]")
    ReportConfig.from_mapping({k: tables[k] for k in ("payload", "springs", "report")
                               if k in tables}, where)
    from_mapping(ViewParams, tables.get("view", {}), f"{where} [view]")


def add_motion_option(parser: argparse.ArgumentParser, run: Callable[[argparse.Namespace], int],
                      json_name: str | None, named: tuple[str, ...] = (),
                      help: str = MOTION_HELP) -> None:
    """Add ``--motion FILE`` and ``--cycle`` to a subcommand's parser and set its ``func`` to
    ``run``, wrapped: after a command with ``--motion`` ran (or failed after writing), the
    log's quality figures are printed and added to ``<--out>/<json_name>`` as
    ``motion_quality`` (None: the command writes no JSON file). ``named``: values of
    ``--motion`` that name a generated motion instead of a log (``hexaleg view``'s ``gait``,
    ``transform``)."""
    parser.add_argument("--motion", metavar="FILE", help=help)
    parser.add_argument("--cycle", default="auto", help=CYCLE_HELP)
    parser.set_defaults(func=functools.partial(_run_with_motion, run, json_name, named))


def _run_with_motion(run: Callable[[argparse.Namespace], int], json_name: str | None,
                     named: tuple[str, ...], args: argparse.Namespace) -> int:
    if (args.motion is None or args.motion in named) and args.cycle != "auto":
        raise InvalidParameterError("--cycle", args.cycle, "--cycle only with --motion FILE "
                                    "(the generated gait is one cycle already)")
    try:
        return run(args)
    finally:
        scenario = getattr(args, "scenario", None)
        if scenario is not None and scenario.recorded is not None:
            from hexaleg.scenario.logged import motion_quality

            for line in motion_quality(scenario.recorded).lines():
                print(f"motion: {line}")
            if json_name is not None:
                _add_quality(Path(args.out) / json_name, scenario)


def _add_quality(path: Path, scenario: Scenario) -> None:
    """Add ``motion_quality`` (:func:`hexaleg.scenario.logged.quality_data`) to a written JSON
    file (skipped when the command wrote none, e.g. it failed before writing)."""
    from hexaleg.config import read_json, write_file
    from hexaleg.quantities import json_text
    from hexaleg.scenario.logged import quality_data

    if not path.is_file() or scenario.recorded is None:
        return
    data = read_json(path, "the command's JSON")
    data["motion_quality"] = quality_data(scenario.recorded)
    write_file(path, json_text(data), "the command's JSON")  # never through a link there


def add_quiet(parser: argparse.ArgumentParser) -> None:
    """Add ``--quiet``: no status lines on stderr (the answer, warnings and errors still
    print)."""
    parser.add_argument("--quiet", "-q", action="store_true",
                        help="print no progress lines on stderr (the answer, warnings and "
                             "errors still print)")


def say(command: str, message: str) -> None:
    """Print one status line of ``hexaleg <command>`` on stderr."""
    print(f"hexaleg {command}: {message}", file=sys.stderr, flush=True)


def progress_of(args: argparse.Namespace, command: str) -> Callable[[str], None] | None:
    """The status-line printer of ``command`` (:func:`say`), or None under ``--quiet``."""
    if getattr(args, "quiet", False):
        return None
    return functools.partial(say, command)


def print_warnings(lines: Sequence[str]) -> None:
    """Print a run's warnings (:meth:`hexaleg.scenario.scenario.Scenario.warnings`), one
    ``warning:`` line each."""
    for line in lines:
        print(f"warning: {line}")


def print_findings(findings: list) -> None:
    """Print the sanity checks' findings (:mod:`hexaleg.robot.sanity`) as warnings."""
    print_warnings([finding.message for finding in findings])


__all__ = ["CYCLE_HELP", "MOTION_HELP", "add_motion_option", "add_quiet", "check_tables",
           "load_run", "print_findings", "print_warnings", "progress_of", "say"]
