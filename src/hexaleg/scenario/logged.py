"""A run on a robot's own log (:func:`hexaleg.load_motion`) instead of the generated gait.

The run (:class:`~hexaleg.scenario.scenario.Scenario`) reads the log with :func:`logged_motion`
(``cycle="auto"``: one periodic cycle, which the simulation needs) and refuses the gait
parameters that no longer apply (:func:`refuse_gait_table`); the commands print its quality
figures and write them to their JSON file as ``motion_quality`` (every number
``{value, unit}``, :func:`quality_data`).
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

from hexaleg.errors import InvalidParameterError
from hexaleg.motion.recorded.load import load_motion
from hexaleg.motion.recorded.quality import MotionQuality
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.model import Robot


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
    return load_motion(robot, path, cycle=parse_cycle(cycle), periodic=True)


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
    report = motion.info.get("report") if motion.info else None
    if not isinstance(report, MotionQuality):
        raise InvalidParameterError("motion", "a generated gait",
                                    "a motion loaded from a log (hexaleg.load_motion)")
    return report


def quality_data(motion: Motion) -> dict[str, Any]:
    """``motion_quality`` of the JSON files (:meth:`MotionQuality.to_dict`)."""
    return motion_quality(motion).to_dict()


def quality_note(motion: Motion) -> str:
    """One line for a page's notes: where the motion came from and how good it is."""
    q = motion_quality(motion)
    plural = "s" if q.cycles != 1 else ""
    return (f"the motion is the log {q.path} (not a generated gait): {q.rows} rows at "
            f"{q.rate:.1f} Hz, period {q.period:.4f} s from {q.cycles} cycle{plural}, noise "
            f"{q.noise:.2e} rad, stance from {q.stance_source}, base from {q.base_source}, "
            f"stance-foot slip rms {q.slip:.4f} m/s")


__all__ = ["logged_motion", "motion_quality", "parse_cycle", "quality_data",
           "quality_note", "refuse_gait_table"]
