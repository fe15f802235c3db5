"""Exceptions raised by hexaleg.

Every error that hexaleg raises on bad input derives from :class:`HexalegError`, names the bad
value and says what is allowed. Callers can catch ``HexalegError`` to handle any of them.
"""

from __future__ import annotations

from collections.abc import Iterable


class HexalegError(Exception):
    """Base class of every error hexaleg raises on bad input or an impossible request."""


class RobotModelError(HexalegError):
    """A robot description (URDF/SRDF) is missing, malformed, or lacks the expected legs/feet."""


def did_you_mean(name: str, valid: Iterable[str]) -> str:
    """``" (did you mean 'x'?)"`` for the valid name closest to ``name`` — the same but for
    case, else the nearest by difflib's ratio ≥ 0.6 — or ``""``."""
    import difflib

    options = list(valid)
    same = [v for v in options if v.lower() == name.lower() and v != name]
    close = same or difflib.get_close_matches(name, options, n=1)
    return f" (did you mean {close[0]!r}?)" if close else ""


class UnknownNameError(HexalegError, KeyError):
    """A name (joint, pose, robot, parameter, key, ...) is not one of the valid names.

    Args:
        kind: What the name is, e.g. ``"joint"`` or ``"pose"``.
        name: The name that was given.
        valid: The names that are allowed.
    """

    def __init__(self, kind: str, name: object, valid: Iterable[object]) -> None:
        self.kind = kind
        self.name = name
        self.valid = sorted(str(v) for v in valid)
        super().__init__(
            f"unknown {kind} {name!r}{did_you_mean(str(name), self.valid)}; valid "
            f"{_plural(kind)} are: {', '.join(self.valid) or '(none)'}"
        )

    def __str__(self) -> str:  # KeyError would repr() the message otherwise
        return str(self.args[0])

    def __reduce__(self) -> tuple:  # rebuild from the constructor's arguments (process pools)
        return (type(self), (self.kind, self.name, self.valid))


class InvalidParameterError(HexalegError, ValueError):
    """A parameter value is out of its allowed range, of the wrong type, or not finite.

    Args:
        name: Parameter name.
        value: The value that was given.
        allowed: Human-readable description of what is allowed, e.g. ``"> 0"``.
    """

    def __init__(self, name: str, value: object, allowed: str) -> None:
        self.name = name
        self.value = value
        self.allowed = allowed
        super().__init__(f"invalid {name} = {value!r}; allowed: {allowed}")

    def __reduce__(self) -> tuple:  # process pools: rebuild from the constructor's arguments,
        # then restore every attribute (a subclass's own fields, e.g. ``nearest``, included)
        return (type(self), (self.name, self.value, self.allowed), self.__dict__)


class SpringDesignError(InvalidParameterError):
    """No buildable spring meets a requirement: names the binding limit, its value, what would
    allow a spring, and carries the nearest spring that violates it (or None).

    Args:
        name: The binding limit (e.g. ``"max_outer_diameter"``).
        value: Its value.
        allowed: What would make a spring possible, naming the nearest one.
        nearest: The nearest spring found (a
            :class:`hexaleg.design.springs.torsion_spring.TorsionSpring`), or None.
    """

    def __init__(self, name: str, value: object, allowed: str, nearest: object = None) -> None:
        super().__init__(name, value, allowed)
        self.nearest = nearest


class ConfigError(HexalegError):
    """A configuration file (TOML) cannot be read or has keys/values that are not allowed."""


class UnreachableTargetError(HexalegError):
    """A foot target lies outside the workspace of its leg (or needs a joint beyond its limits).

    The leg solvers fill in what they know; a field is None when not known.

    Args:
        message: The message (names the leg, the time and the distance out of reach).
        leg: Leg name.
        t: Time of the sample, s.
        index: Index of the sample in the solved trajectory.
        target: The foot target in the base frame, (x, y, z), m.
        distance: How far the target is out of reach (or where Newton stopped from it), m; None
            for a joint beyond its limits or a target on the coxa axis.
    """

    def __init__(self, message: str, *, leg: str | None = None, t: float | None = None,
                 index: int | None = None, target: tuple[float, ...] | None = None,
                 distance: float | None = None) -> None:
        super().__init__(message)
        self.leg, self.t, self.index = leg, t, index
        self.target, self.distance = target, distance


class GaitReachError(UnreachableTargetError):
    """A gait's foot target is out of reach: the leg, the time and phase, and what to change.

    Raised by :func:`hexaleg.motion.legged.sample_gait` (diagnosis in
    :mod:`hexaleg.motion.reach`); the solver's :class:`UnreachableTargetError` is its cause.

    Args:
        message: The message: the solver's, then the phase, the parameter and a working value.
        phase: ``"stance"`` or ``"swing"`` at the failing sample.
        parameter: The gait parameter most likely responsible: ``"step_height"``,
            ``"stride_length"``, ``"speed"``, ``"body_height"``, ``"foot_radius"`` or
            ``"stand"`` (the robot's stand pose, when its legs are at the workspace edge).
        value: That parameter's value in the failing gait (None for ``"stand"``).
        suggestion: ``GaitParams`` fields and values that make every leg's targets reachable,
            e.g. ``{"step_height": 0.26}``; empty when none was found.
        stand: For ``parameter == "stand"``: a bent-knee stand configuration (nq,) whose feet
            are the suggested footholds, or None.
        **data: The fields of :class:`UnreachableTargetError`.
    """

    def __init__(self, message: str, *, phase: str = "", parameter: str = "",
                 value: float | None = None, suggestion: dict[str, float] | None = None,
                 stand: object = None, **data: object) -> None:
        super().__init__(message, **data)  # type: ignore[arg-type]
        self.phase, self.parameter, self.value = phase, parameter, value
        self.suggestion = {} if suggestion is None else suggestion
        self.stand = stand


class InfeasibleForcesError(HexalegError):
    """No ground reaction forces satisfy the dynamics and the contact constraints."""


class TorqueLimitError(HexalegError):
    """A motor torque exceeds its limit."""


class StaticMarginError(InvalidParameterError):
    """A statically stable gait cannot keep the static margin asked for: no body shift keeps
    the centre of mass that far inside every support polygon of the cycle. Raised while the
    gait is made, before any force program runs.

    Args:
        name: The parameter (``"min_static_margin"``).
        value: The margin asked for, m.
        allowed: The largest margin the gait allows and what to change.
        largest: That largest margin, m (negative: not even the polygons' edges can be kept).
    """

    def __init__(self, name: str, value: object, allowed: str, largest: float = 0.0) -> None:
        super().__init__(name, value, allowed)
        self.largest = largest


class OutputError(HexalegError):
    """An output file or directory cannot be written."""


class DirectoryLockedError(OutputError):
    """An output directory is being written by another running process (a sweep, or a
    command's run: :class:`hexaleg.outputs.directory.OutputFolder`).

    Args:
        message: The message: who holds the directory and what to do.
        directory: The directory.
        pid: The holder's process id, if known.
        host: The holder's host name, if known.
        started: When the holder took the lock, if known.
    """

    def __init__(self, message: str, *, directory: object = None, pid: object = None,
                 host: object = None, started: object = None) -> None:
        super().__init__(message)
        self.directory, self.pid, self.host, self.started = directory, pid, host, started


class HexalegWarning(UserWarning):
    """Something hexaleg did differently from what was asked, or a result to read with care
    (e.g. a sweep part file that was unreadable and is recomputed); the message says why."""


class ExecutorError(HexalegError):
    """A sweep executor (e.g. a Dask scheduler) cannot be reached or failed."""


class DivergedSolveError(HexalegError):
    """An optimal-control solve left the finite numbers: a rollout of its dynamics from the
    start it was given reached non-finite states (the message says on which knots and what
    start to give it)."""


class SimulationError(HexalegError):
    """A forward simulation did not walk: the robot fell or the integration diverged (the
    message says when and how)."""


def _plural(kind: str) -> str:
    """``kind`` in the plural: "spring family" → "spring families", "key in X" → "keys in X"."""
    head, sep, tail = kind.partition(" in ")
    noun = (head[:-1] + "ies" if head.endswith("y") and head[-2:-1] not in "aeiou"
            else head + ("es" if head.endswith(("s", "x", "ch", "sh")) else "s"))
    return noun + sep + tail
