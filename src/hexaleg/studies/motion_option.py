"""``--motion FILE``: a robot's own log (:func:`hexaleg.load_motion`) instead of the generated gait.

``hexaleg report``, ``design``, ``simulate``, ``view`` and ``sweep`` take it through
:func:`add_motion_option`; their loaders read the log with :func:`logged_motion`
(``cycle="auto"``: one periodic cycle, which the simulation needs) and refuse the gait
parameters that no longer apply (:func:`refuse_gait_table`). After the command ran, its quality
figures are printed and written to the command's JSON file as ``motion_quality`` (every number
``{value, unit}``, :func:`quality_data`).
"""

from __future__ import annotations

import argparse
import functools
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

from hexaleg.config import json_text, read_json, write_file
from hexaleg.errors import InvalidParameterError

if TYPE_CHECKING:  # the parser imports this module: the loaders only when a log is read
    from hexaleg.motion.recorded.quality import MotionQuality
    from hexaleg.motion.trajectory import Motion
    from hexaleg.robot.model import Robot

MOTION_HELP = ("a log of the robot's own gait (CSV with a header row or NPZ: time, joint angles, "
               "optional base pose and contact_<LEG>; or a ROS 2 bag directory; docs/motion.md) "
               "instead of the generated gait")
"""What ``--motion`` takes."""
CYCLE_HELP = ("with --motion: 'auto' (the period found and the log's cycles averaged into one "
              "periodic cycle), 'whole' (the log is exactly one cycle, taken as periodic) or "
              "T0:T1 (one cycle's window, s from the first stamp) (default: %(default)s)")
"""What ``--cycle`` takes."""
UNITS: dict[str, str] = {"rows": "rows", "rate": "Hz", "filled": "values", "noise": "rad",
                         "cutoff": "Hz", "window": "samples", "period": "s", "cycles": "cycles",
                         "correlation": "1", "spread": "rad", "stance_height": "m",
                         "stance_speed": "m/s", "slip": "m/s", "slip_max": "m/s"}
"""The unit of each number of :class:`~hexaleg.motion.recorded.quality.MotionQuality`."""

_LOADED: dict[str, Motion] = {}
"""Log path → the motion a command read from it (its quality printed and written after the
run, :func:`add_motion_option`), removed when that command ends."""


def add_motion_option(parser: argparse.ArgumentParser, run: Callable[[argparse.Namespace], int],
                      json_name: str | None, named: tuple[str, ...] = (),
                      help: str = MOTION_HELP) -> None:
    """Add ``--motion FILE`` to a subcommand's parser and set its ``func`` to ``run``, wrapped:
    with ``--motion``, after the command ran (or failed after writing), the log's quality
    figures are printed and added to ``<--out>/<json_name>`` as ``motion_quality`` (None: the
    command writes no JSON file); ``--cycle`` says which part of the log is the cycle
    (:func:`logged_motion`). ``named``: values of ``--motion`` that name a generated motion
    instead of a log (``hexaleg view``'s ``gait``, ``transform``)."""
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
    finally:  # the log read for this command only: a later command reads it afresh
        motion = _LOADED.pop(str(Path(args.motion)), None) if args.motion else None
        if motion is not None:
            for line in motion_quality(motion).lines():
                print(f"motion: {line}")
            if json_name is not None:
                add_quality(Path(args.out) / json_name, motion)


def parse_cycle(cycle: str) -> str | tuple[float, float]:
    """``--cycle``: ``"auto"``, ``"whole"`` or ``"T0:T1"`` (s) as :func:`hexaleg.load_motion`'s
    ``cycle``.

    Raises:
        InvalidParameterError: anything else (named, with what is allowed).
    """
    if cycle in ("auto", "whole"):
        return cycle
    parts = cycle.split(":")
    try:
        t0, t1 = (float(p) for p in parts)
    except ValueError:
        raise InvalidParameterError("--cycle", cycle, "auto, whole or T0:T1 (s from the log's "
                                    "first stamp, e.g. 2.0:3.0)") from None
    return t0, t1


def logged_motion(robot: Robot, path: str | Path, cycle: str = "auto") -> Motion:
    """The motion of the log at ``path`` as one periodic cycle: found and averaged
    (``"auto"``), the whole log taken as one cycle (``"whole"``) or a window ``"T0:T1"`` of one
    cycle (:func:`parse_cycle`); periodic in every case (the simulation repeats it).

    Raises:
        ConfigError, UnknownNameError, InvalidParameterError: a bad ``cycle``; the log's named
            bad input (:func:`hexaleg.motion.recorded.load.load_motion`).
    """
    from hexaleg.motion.recorded.load import load_motion

    motion = load_motion(robot, path, cycle=parse_cycle(cycle), periodic=True)
    _LOADED[str(Path(path))] = motion
    return motion


def refuse_gait_table(data: Mapping[str, Any], where: str, path: str | Path) -> None:
    """Refuse a ``[gait]`` table given together with ``--motion``.

    Raises:
        InvalidParameterError: names the table's keys and says what to do instead.
    """
    if "gait" in data:
        keys = ", ".join(data["gait"]) if isinstance(data["gait"], Mapping) else data["gait"]
        raise InvalidParameterError(
            f"{where} [gait]", keys or "{}",
            f"no [gait] table with --motion {path}: the logged motion is the gait, so gait "
            "parameters do not apply; remove the [gait] table or the --motion option")


def motion_quality(motion: Motion) -> MotionQuality:
    """The quality report of a loaded log (``info["report"]``).

    Raises:
        InvalidParameterError: a motion that was not loaded from a log.
    """
    from hexaleg.motion.recorded.quality import MotionQuality

    report = motion.info.get("report") if motion.info else None
    if not isinstance(report, MotionQuality):
        raise InvalidParameterError("motion", "a generated gait",
                                    "a motion loaded from a log (hexaleg.load_motion)")
    return report


def quality_data(motion: Motion) -> dict[str, Any]:
    """``motion_quality`` of the JSON files: every number ``{value, unit}`` (stance fractions
    per leg as fractions of the samples, ``"1"``); None stays None; strings and flags as they
    are."""
    out: dict[str, Any] = {}
    for key, value in motion_quality(motion).to_dict().items():
        if isinstance(value, dict) and "unit" in value:
            value = value["value"]
        if key == "stance_fractions":
            out[key] = {leg: {"value": float(f), "unit": "1"} for leg, f in value.items()}
        elif key in UNITS:
            out[key] = None if value is None else {"value": value, "unit": UNITS[key]}
        else:
            out[key] = value
    return out


def quality_note(motion: Motion) -> str:
    """One line for a page's notes: where the motion came from and how good it is."""
    q = motion_quality(motion)
    plural = "s" if q.cycles != 1 else ""
    return (f"the motion is the log {q.path} (not a generated gait): {q.rows} rows at "
            f"{q.rate:.1f} Hz, period {q.period:.4f} s from {q.cycles} cycle{plural}, noise "
            f"{q.noise:.2e} rad, stance from {q.stance_source}, base from {q.base_source}, "
            f"stance-foot slip rms {q.slip:.4f} m/s")


def add_quality(path: Path, motion: Motion) -> None:
    """Add ``motion_quality`` (:func:`quality_data`) to a written JSON file (skipped when the
    command wrote none, e.g. it failed before writing)."""
    if not path.is_file():
        return
    data = read_json(path, "the command's JSON")
    data["motion_quality"] = quality_data(motion)
    write_file(path, json_text(data), "the command's JSON")  # never through a link there


__all__ = ["add_motion_option", "add_quality", "logged_motion", "motion_quality",
           "parse_cycle", "quality_data", "quality_note", "refuse_gait_table"]
