"""Checked, frozen fields of a robot description: stand, heading, legs, gait overrides, moves.

Helpers of :class:`hexaleg.robot.description.RobotDescription`: they turn TOML values into the
description's frozen fields and name the bad value and what is allowed.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from types import MappingProxyType
from typing import Any

import numpy as np

from hexaleg.checks import is_real
from hexaleg.config import from_mapping
from hexaleg.errors import ConfigError, InvalidParameterError, UnknownNameError
from hexaleg.robot.feet import LegSpec


def check_stand(name: str, stand: Any) -> Any:
    """A stand checked and frozen (see :class:`RobotDescription`)."""
    if stand is None or isinstance(stand, str):
        return stand
    allowed = ("an SRDF group_state name, joint name → finite angle (rad), or {body_height = "
               "h (m), feet = {leg = [x, y]}, joints = {joint = angle (rad)}}")
    if not isinstance(stand, Mapping):
        raise InvalidParameterError(f"{name}: stand", stand, allowed)
    if "body_height" in stand or "feet" in stand or "joints" in stand:
        keys = ("body_height", "feet", "joints")
        unknown = [k for k in stand if k not in keys]
        if unknown:
            raise UnknownNameError(f"key in {name}: stand", unknown[0], keys)
        if not is_real(stand.get("body_height")) or not stand["body_height"] > 0:
            raise InvalidParameterError(f"{name}: stand.body_height", stand.get("body_height"),
                                        "a height > 0 (m) of the base above the feet")
        feet = stand.get("feet", {})
        if not isinstance(feet, Mapping) or not all(
                isinstance(v, (list, tuple)) and len(v) == 2 and all(is_real(x) for x in v)
                for v in feet.values()):
            raise InvalidParameterError(f"{name}: stand.feet", feet, "{leg = [x, y]} (m)")
        joints = stand.get("joints", {})
        if not isinstance(joints, Mapping) or not all(
                isinstance(k, str) and is_real(v) for k, v in joints.items()):
            raise InvalidParameterError(f"{name}: stand.joints", joints,
                                        "{joint = angle (rad)}: the pose of joints on no leg")
        return MappingProxyType({"body_height": float(stand["body_height"]), "feet": FrozenTable(
            {k: tuple(float(x) for x in v) for k, v in feet.items()}),
            "joints": FrozenTable({k: float(v) for k, v in joints.items()})})
    if not all(isinstance(k, str) and is_real(v) for k, v in stand.items()):
        raise InvalidParameterError(f"{name}: stand", stand, allowed)
    return MappingProxyType({k: float(v) for k, v in stand.items()})


AXES = {"+x": (1.0, 0.0, 0.0), "-x": (-1.0, 0.0, 0.0), "+y": (0.0, 1.0, 0.0),
        "-y": (0.0, -1.0, 0.0)}
"""Headings by name."""


def axis(text: str, where: str) -> tuple[float, float, float]:
    """The heading named ``text`` (a key of :data:`AXES`)."""
    if text not in AXES:
        raise UnknownNameError(f"heading in {where}", text, (*AXES, "[x, y, 0]"))
    return AXES[text]


def horizontal_axis(name: str, value: Any,
                    allowed: str = "a horizontal base axis [x, y, 0], not zero") -> np.ndarray:
    """``value`` checked as a horizontal base axis (a robot's heading), shape (3,), not
    normalised: finite, ``|z| ≤ 1e-12`` and ``|(x, y)| ≥ 1e-9``.

    Raises:
        InvalidParameterError: otherwise, naming ``name``, the value and ``allowed``.
    """
    try:
        h = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        h = np.zeros(0)
    if h.shape != (3,) or not np.all(np.isfinite(h)) or abs(h[2]) > 1e-12 or \
            np.hypot(h[0], h[1]) < 1e-9:
        raise InvalidParameterError(name, value, allowed)
    return h


def vector3(name: str, value: Any, unit: str) -> tuple[float, float, float]:
    """``value`` checked as three finite numbers (a point, ``unit`` says in what), as a tuple.

    Raises:
        InvalidParameterError: otherwise, naming ``name`` and the value.
    """
    if not (isinstance(value, (list, tuple)) and len(value) == 3 and all(map(is_real, value))):
        raise InvalidParameterError(name, value, f"[x, y, z] ({unit}, finite)")
    return (float(value[0]), float(value[1]), float(value[2]))


def heading(name: str, heading: Any) -> tuple[float, float, float]:
    """A description's heading checked (:func:`horizontal_axis`, or a name of :data:`AXES`),
    as a tuple."""
    if isinstance(heading, str):
        return axis(heading, name)
    h = horizontal_axis(f"{name}: heading", heading,
                        "a horizontal base axis [x, y, 0] or one of +x, -x, +y, -y")
    return (float(h[0]), float(h[1]), 0.0)


def legs_table(legs: Any, where: str) -> tuple[LegSpec, ...]:
    """``[[robot.legs]]`` tables → leg specs; ``foot`` a frame name or ``{link, point}``."""
    if not isinstance(legs, list) or not legs or not all(isinstance(g, Mapping) for g in legs):
        raise ConfigError(f"{where}: expected [[robot.legs]] tables with name, joints and an "
                          "optional foot")
    out = []
    for i, leg in enumerate(legs):
        leg = dict(leg)
        foot = leg.get("foot")
        if isinstance(foot, Mapping):
            unknown = [k for k in foot if k not in ("link", "point")]
            if unknown or not isinstance(foot.get("link"), str) or not isinstance(
                    foot.get("point"), list):
                raise ConfigError(f"{where} legs[{i}].foot = {dict(foot)!r}; expected a frame "
                                  "name or {link = \"<link>\", point = [x, y, z]}")
            leg["foot"], leg["point"] = foot["link"], tuple(foot["point"])
        if isinstance(leg.get("joints"), list):
            leg["joints"] = tuple(leg["joints"])
        out.append(from_mapping(LegSpec, leg, f"{where} legs[{i}]"))
    return tuple(out)


def diameters_table(name: str, kinds: tuple[str, ...] | None, table: Any,
                    key: str = "max_outer_diameter", low_open: bool = True) -> FrozenTable:
    """A description's table of diameters checked: joint class → a diameter (m), > 0 (or ≥ 0
    with ``low_open`` False); ``key`` names the table in the errors."""
    allowed = f"a diameter {'>' if low_open else '>='} 0 (m)"
    if not isinstance(table, Mapping):
        raise InvalidParameterError(f"{name}: {key}", table,
                                    "a table of joint class = diameter (m)")
    for kind, value in table.items():
        if kinds is not None and kind not in kinds:
            raise UnknownNameError(f"{name}: {key} joint class", kind, kinds)
        if not is_real(value) or value < 0 or (low_open and value == 0):
            raise InvalidParameterError(f"{name}: {key}.{kind}", value, allowed)
    return FrozenTable({str(k): float(v) for k, v in table.items()})


MOVE_KEYS = ("amplitude", "phase")
"""The keys of a joint's entry in a description's ``moves`` table."""


def moves_table(name: str, table: Any) -> FrozenTable:
    """A description's ``moves`` checked: joint → ``{amplitude ≥ 0, phase}`` (rad, finite),
    frozen as joint → (amplitude, phase); the joints are checked against the robot on loading
    (:func:`hexaleg.robot.stand.checked_moves`)."""
    if not isinstance(table, Mapping):
        raise InvalidParameterError(f"{name}: moves", table, "a table of joint = {amplitude, "
                                    "phase} (rad) for joints on no leg")
    out = {}
    for joint, entry in table.items():
        if not isinstance(entry, Mapping):
            raise InvalidParameterError(f"{name}: moves.{joint}", entry,
                                        "a table {amplitude = rad, phase = rad}")
        for key in entry:
            if key not in MOVE_KEYS:
                raise UnknownNameError(f"{name}: moves.{joint} key", key, MOVE_KEYS)
        amplitude, phase = entry.get("amplitude", 0.0), entry.get("phase", 0.0)
        if not is_real(amplitude) or not np.isfinite(amplitude) or amplitude < 0:
            raise InvalidParameterError(f"{name}: moves.{joint}.amplitude", amplitude,
                                        "an amplitude ≥ 0 (rad)")
        if not is_real(phase) or not np.isfinite(phase):
            raise InvalidParameterError(f"{name}: moves.{joint}.phase", phase,
                                        "a finite phase (rad)")
        out[str(joint)] = (float(amplitude), float(phase))
    return FrozenTable(out)


class FrozenTable(Mapping[str, Any]):
    """A read-only, hashable, picklable table of plain values (a description's gait overrides).

    Unlike :class:`types.MappingProxyType` it can be pickled and deep-copied, like the frozen
    dataclasses it sits in; equal to any mapping with the same items.
    """

    __slots__ = ("_data",)

    def __init__(self, data: Mapping[str, Any]) -> None:
        self._data = dict(data)

    def __getitem__(self, key: str) -> Any:
        return self._data[key]

    def __iter__(self) -> Iterator[str]:
        return iter(self._data)

    def __len__(self) -> int:
        return len(self._data)

    def __hash__(self) -> int:
        return hash(frozenset(self._data.items()))

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self._data!r})"


def plain(value: Any) -> Any:
    """A TOML value with its lists (at any depth) made tuples, e.g. leg groups."""
    if isinstance(value, (list, tuple)):
        return tuple(plain(v) for v in value)
    return value
