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
of ``{"breakpoint", "stiffness"}``. An angle past which nothing acts (:func:`idle_fields`: every
magnitude there at most :data:`~hexaleg.design.families.family.ZERO_MAGNITUDE`) is no property
of the spring — any angle gives the same law — so it is written without a value, with the reason,
as the design's tables write it (:func:`hexaleg.design.springs.table.magnitudes_table`)::

    "theta_plus": {"value": null, "unit": "rad",
                   "note": "nothing acts past it: any angle gives the same spring"}

:func:`spring_from_entry` rebuilds the identical law, an idle angle at a place that changes
nothing (:func:`_placed`): the same torque and energy at every angle (``hexaleg simulate`` reads
the springs of ``design.json`` this way).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from typing import Any

from hexaleg.checks import one_of
from hexaleg.design.families import FAMILIES, IDLE, LINEAR_GAP, ZERO_MAGNITUDE, family
from hexaleg.errors import ConfigError, InvalidParameterError, UnknownNameError
from hexaleg.robot.springs import Spring, StiffeningSpring

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
STOPS = ("theta_k", "theta_minus", "theta_plus", "contact")
"""The angle fields a term acts past (a stiffening spring's breakpoints besides): the ones
:func:`idle_fields` may find idle and an entry may give as null."""


def family_of(spring: Spring) -> str:
    """The family name of a spring law (a key of :data:`CLASSES`)."""
    for name, cls in CLASSES.items():
        if type(spring) is cls:
            return name
    raise UnknownNameError("spring class", type(spring).__name__,
                           [c.__name__ for c in CLASSES.values()])


def idle_fields(spring: Spring) -> tuple[str, ...]:
    """The angle fields of ``spring`` past which nothing acts: every magnitude of the terms at
    the angle at most :data:`~hexaleg.design.families.family.ZERO_MAGNITUDE` in size
    (:meth:`hexaleg.design.families.family.Family.idle` on the law's own terms: a term's name is
    its family's magnitude name). ``theta_k``, both stops at once, when both are idle; a
    stiffening spring's stage as ``above[i]`` / ``below[i]``; none for a linear spring (its
    reference is where its torque is given, not a stop)."""
    name = family_of(spring)
    if isinstance(spring, StiffeningSpring):
        return tuple(f"{side}[{i}]" for side in ("above", "below")
                     for i, (_, k) in enumerate(getattr(spring, side)) if k <= ZERO_MAGNITUDE)
    if name == "linear":
        return ()
    magnitudes = dict(zip((t.name for t in spring.terms()), spring.magnitudes(), strict=True))
    idle = family(name).idle(magnitudes)
    if getattr(spring, "theta_k", None) is not None and all(a in idle for a in STOPS[1:3]):
        idle = (*idle, "theta_k")
    return tuple(a for a in idle if getattr(spring, a) is not None)


def spring_entry(joint: str, spring: Spring) -> dict[str, Any]:
    """The JSON entry of the spring on ``joint`` (module docstring): an idle angle
    (:func:`idle_fields`) ``{"value": null, "unit": "rad", "note": IDLE}``."""
    idle = idle_fields(spring)
    none = {"value": None, "unit": "rad", "note": IDLE}
    params: dict[str, Any] = {}
    for f in dataclasses.fields(spring):  # type: ignore[arg-type]
        value = getattr(spring, f.name)
        if value is None:
            continue
        if f.name in TEXT_FIELDS:
            params[f.name] = value
        elif f.name in ("above", "below"):
            params[f.name] = [{"breakpoint": (none if f"{f.name}[{i}]" in idle
                                              else {"value": float(a), "unit": "rad"}),
                               "stiffness": {"value": float(k), "unit": "N·m/rad"}}
                              for i, (a, k) in enumerate(value)]
        elif f.name in idle:
            params[f.name] = none
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
            kwargs[name] = _number(value, UNITS[name], f"{where}.{name}", idle=name in STOPS)
    nulls = [k for k, v in kwargs.items() if v is None]
    try:
        spring = cls(**_placed(family, kwargs))
    except InvalidParameterError as e:
        if type(e) is not InvalidParameterError:
            raise
        raise InvalidParameterError(f"{where}.{e.name}", e.value, e.allowed) from None
    for name in nulls:
        if name not in idle_fields(spring):
            raise InvalidParameterError(f"{where}.{name}", None, "a value: something acts past "
                                        "it (an angle is null only where nothing does, "
                                        f"{ZERO_MAGNITUDE:g} or less)")
    return spring


def _placed(family: str, kwargs: Mapping[str, Any]) -> dict[str, Any]:
    """The law's fields with each idle angle read back as null (module docstring) placed where
    it changes nothing and the law's order holds: at the other stop (a dead zone's, which needs
    θ⁻ < θ⁺, :data:`~hexaleg.design.families.LINEAR_GAP` beside it), at 0 when both stops or a
    one-sided spring's contact are idle; a stiffening spring's idle stage left out (a law of
    idle stages only: one stage of stiffness 0 at 0)."""
    out = dict(kwargs)
    if family == "stiffening":
        for side in ("above", "below"):
            out[side] = tuple(s for s in out.get(side, ()) if s[0] is not None)
        if not out["above"] and not out["below"]:
            out["above"] = ((0.0, 0.0),)
        return out
    gap = LINEAR_GAP if family == "dead_zone" else 0.0
    if out.get("theta_k", 0.0) is None:
        out["theta_k"] = gap or 0.0
    lo, hi = out.get("theta_minus", 0.0), out.get("theta_plus", 0.0)
    if lo is None and hi is None:
        out["theta_minus"], out["theta_plus"] = -gap / 2, gap / 2
    elif lo is None:
        out["theta_minus"] = hi - gap
    elif hi is None:
        out["theta_plus"] = lo + gap
    if out.get("contact", 0.0) is None:
        out["contact"] = 0.0
    return out


def _stages(value: Any, where: str) -> tuple[tuple[Any, Any], ...]:
    """A stiffening spring's ``above`` / ``below``: ``[{"breakpoint", "stiffness"}, …]``; an
    idle stage's breakpoint None (its stiffness checked at most the design's zero)."""
    if not isinstance(value, list) or not all(isinstance(s, Mapping) for s in value):
        raise ConfigError(f"{where} = {value!r}; expected a list of "
                          "{\"breakpoint\": …, \"stiffness\": …}")
    out = []
    for i, s in enumerate(value):
        a = _number(s.get("breakpoint"), "rad", where, idle=True)
        k = _number(s.get("stiffness"), "N·m/rad", where)
        if a is None and not (isinstance(k, (int, float)) and abs(k) <= ZERO_MAGNITUDE):
            raise InvalidParameterError(f"{where}[{i}].breakpoint", None,
                                        f"a value: its stage's stiffness {k!r} N·m/rad acts "
                                        f"past it (null only at {ZERO_MAGNITUDE:g} or less)")
        out.append((a, k))
    return tuple(out)


def _number(q: Any, unit: str, where: str, idle: bool = False) -> Any:
    """The value of ``{"value", "unit"}`` in ``unit`` (an ``idle`` angle's may be null)."""
    if not isinstance(q, Mapping) or q.get("unit") != unit or "value" not in q \
            or (q["value"] is None and not idle):
        raise ConfigError(f"{where} = {q!r}; expected {{\"value\": …, \"unit\": \"{unit}\"}}"
                          + (" (null only for an angle past which nothing acts)" if idle else ""))
    return q["value"]
