"""A spring law as JSON and back: how ``design.json`` hands its springs to other tools.

One entry per sprung joint::

    {"family": "one_sided", "joint": "LF_femur",
     "parameters": {"stiffness": {"value": 0.0205, "unit": "N·m/rad"},
                    "contact": {"value": 0.61, "unit": "rad"},
                    "side": "above",
                    "preload": {"value": 0.0557, "unit": "N·m"}}}

``parameters`` are the fields of the family's spring class
(:mod:`hexaleg.robot.springs`), absolute joint angles, SI; every number ``{value, unit}``, the
text fields (``side``, ``convention``) plain; a stiffening spring's ``above`` / ``below`` are lists
of ``{"breakpoint", "stiffness"}``. :func:`spring_from_entry` rebuilds the identical law
(``hexaleg simulate`` reads the springs of ``design.json`` this way).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from typing import Any

from hexaleg.checks import one_of
from hexaleg.design.families import FAMILIES, family
from hexaleg.errors import ConfigError, InvalidParameterError, UnknownNameError
from hexaleg.robot.springs import (
    Spring,
)

CLASSES: dict[str, type] = {name: family(name).law for name in FAMILIES}
"""Family name → spring class (:mod:`hexaleg.design.families`)."""
UNITS: dict[str, str] = {
    **dict.fromkeys(("stiffness", "stiffness_minus", "k2"), "N·m/rad"),
    **dict.fromkeys(("theta_k", "theta_minus", "theta_plus", "neutral", "reference", "contact"),
                    "rad"),
    **dict.fromkeys(("preload", "preload_minus", "torque_at_reference"), "N·m"),
    "alpha": "1", "damping": "N·m·s/rad"}
"""Unit of every numeric field of the spring classes (SI)."""
TEXT_FIELDS = ("side", "convention")


def family_of(spring: Spring) -> str:
    """The family name of a spring law (a key of :data:`CLASSES`)."""
    for name, cls in CLASSES.items():
        if type(spring) is cls:
            return name
    raise UnknownNameError("spring class", type(spring).__name__,
                           [c.__name__ for c in CLASSES.values()])


def spring_entry(joint: str, spring: Spring) -> dict[str, Any]:
    """The JSON entry of the spring on ``joint`` (module docstring)."""
    params: dict[str, Any] = {}
    for f in dataclasses.fields(spring):  # type: ignore[arg-type]
        value = getattr(spring, f.name)
        if value is None:
            continue
        if f.name in TEXT_FIELDS:
            params[f.name] = value
        elif f.name in ("above", "below"):
            params[f.name] = [{"breakpoint": {"value": float(a), "unit": "rad"},
                               "stiffness": {"value": float(k), "unit": "N·m/rad"}}
                              for a, k in value]
        else:
            params[f.name] = {"value": float(value), "unit": UNITS[f.name]}
    return {"family": family_of(spring), "joint": joint, "parameters": params}


def spring_from_entry(entry: Mapping[str, Any], where: str = "spring") -> Spring:
    """The spring law of a JSON entry (the inverse of :func:`spring_entry`).

    Args:
        entry: ``{"family", "joint", "parameters"}``.
        where: Where it came from, for errors.

    Raises:
        UnknownNameError: an unknown family or parameter (lists the valid ones).
        ConfigError: a malformed entry or a unit that is not the field's SI unit.
        InvalidParameterError: a value out of range (from the spring class).
    """
    if not isinstance(entry, Mapping) or not isinstance(entry.get("parameters"), Mapping):
        raise ConfigError(f"{where}: expected {{family, joint, parameters}}, got {entry!r}")
    family = one_of(f"{where} family", entry.get("family"), CLASSES)
    cls = CLASSES[family]
    fields = {f.name for f in dataclasses.fields(cls)}
    kwargs: dict[str, Any] = {}
    for name, value in entry["parameters"].items():
        if name not in fields:
            raise UnknownNameError(f"{where} parameter of {family}", name, fields)
        if name in TEXT_FIELDS:
            kwargs[name] = value
        elif name in ("above", "below"):
            kwargs[name] = _stages(value, f"{where}.{name}")
        else:
            kwargs[name] = _number(value, UNITS[name], f"{where}.{name}")
    try:
        return cls(**kwargs)
    except InvalidParameterError as e:
        if type(e) is not InvalidParameterError:
            raise
        raise InvalidParameterError(f"{where}.{e.name}", e.value, e.allowed) from None


def _stages(value: Any, where: str) -> tuple[tuple[float, float], ...]:
    """A stiffening spring's ``above`` / ``below``: ``[{"breakpoint", "stiffness"}, …]``."""
    if not isinstance(value, list) or not all(isinstance(s, Mapping) for s in value):
        raise ConfigError(f"{where} = {value!r}; expected a list of "
                          "{\"breakpoint\": …, \"stiffness\": …}")
    return tuple((_number(s.get("breakpoint"), "rad", where),
                  _number(s.get("stiffness"), "N·m/rad", where)) for s in value)


def _number(q: Any, unit: str, where: str) -> float:
    if not isinstance(q, Mapping) or q.get("unit") != unit or "value" not in q:
        raise ConfigError(f"{where} = {q!r}; expected {{\"value\": …, \"unit\": \"{unit}\"}}")
    return q["value"]
