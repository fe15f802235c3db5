"""The tables of a sweep spec file read into SI values: ``[sweep]`` and ``[contact]`` (the run),
``[gait]`` (fixed or varied gait parameters) and ``[springs.<group>]`` (design parameters, in SI
or the paper's units, ``docs/sweep.md``); :class:`hexaleg.sweep.spec.SweepSpec` checks
and combines them."""

from __future__ import annotations

import warnings
from collections.abc import Callable, Mapping
from typing import Any

from hexaleg.checks import string
from hexaleg.design.evaluator import SPRING_PARAMETERS
from hexaleg.errors import ConfigError, UnknownNameError
from hexaleg.scenario.scenario import Scenario
from hexaleg.sweep.ranges import axis_values
from hexaleg.units import deg_to_rad, nmm_per_deg_to_nm_per_rad

PAPER_UNIT_PARAMETERS: dict[str, tuple[str, Callable[[Any], Any]]] = {
    "k_nmm_per_deg": ("k", nmm_per_deg_to_nm_per_rad),
    "k_minus_nmm_per_deg": ("k_minus", nmm_per_deg_to_nm_per_rad),
    "theta_k_deg": ("theta_k", deg_to_rad),
    "theta_minus_deg": ("theta_minus", deg_to_rad),
    "theta_plus_deg": ("theta_plus", deg_to_rad),
    "offset_deg": ("offset", deg_to_rad),
}
"""Spec keys in the paper's units (N·mm/deg, deg) → (SI parameter, conversion)."""
GAIT_PARAMETERS: tuple[str, ...] = ("period", "duty_factor", "stride_length", "speed",
                                    "step_height", "body_height", "foot_radius", "yaw_rate",
                                    "samples")
"""Scalar :class:`hexaleg.motion.params.GaitParams` fields a sweep may fix or vary."""


def sweep_table(data: Mapping[str, Any], where: str) -> tuple[Scenario, dict[str, Any]]:
    """``[sweep]``, ``[contact]`` and ``[motor]`` → the run and the remaining ``[sweep]`` keys.

    The actuator's one home is ``[motor]``, as in every command; ``[sweep] motor`` (a catalogue
    name) still works, deprecated with a warning saying where it went, and is refused beside
    ``[motor]``.

    Raises:
        ConfigError: ``[sweep] motor`` beside a ``[motor]`` table.
        UnknownNameError: an unknown key, robot or motor (lists the valid ones).
    """
    sweep = dict(data.get("sweep", {}))
    run_keys = {"robot", "motor", "objective"}
    run_table = {k: sweep.pop(k) for k in list(sweep) if k in run_keys}
    named = {k: string(f"sweep.{k}", v) for k, v in run_table.items()}
    motor = data.get("motor")
    if "motor" in named:
        if motor is not None:
            raise ConfigError(f"{where} [sweep] motor = {named['motor']!r} beside a [motor] "
                              "table: the actuator has one home, [motor]; remove [sweep] motor")
        warnings.warn(f"{where} [sweep] motor = {named['motor']!r} is deprecated: the "
                      f"actuator's one home is [motor] (write [motor] base = "
                      f"{named['motor']!r})", DeprecationWarning, stacklevel=2)
        motor = {"base": named["motor"]}
    tables = {"contact": data.get("contact", {}), **({"motor": motor} if motor else {})}
    run = Scenario.from_tables(named.get("robot", "hexaleg"), tables, where)
    if "objective" in named:
        run = run.replace(objective=named["objective"])
    allowed = ("metric", "layout", "chunk_size")
    for key in sweep:
        if key not in allowed:
            raise UnknownNameError(f"key in {where} [sweep]", key, (*allowed, *run_keys))
    return run, sweep


def gait_table(table: Mapping[str, Any]) -> dict[str, Any]:
    """``[gait]`` → gait parameter → value or tuple of values (``samples`` as integers)."""
    gait = {}
    for name, value in table.items():
        if name not in GAIT_PARAMETERS:
            raise UnknownNameError("gait parameter", name, GAIT_PARAMETERS)
        v = axis_values(f"gait.{name}", value)
        if name == "samples":
            v = tuple(int(x) for x in v) if isinstance(v, tuple) else int(v)
        gait[name] = v
    return gait


def spring_tables(tables: Mapping[str, Any], where: str
                   ) -> tuple[dict[str, dict[str, Any]], dict[str, tuple[str, ...]]]:
    """``[springs.<group>]`` tables → (group → SI parameters, group → explicit joints)."""
    springs, joints = {}, {}
    for group, table in tables.items():
        if not isinstance(table, Mapping):
            raise ConfigError(f"{where} [springs.{group}]: expected a table of parameters")
        params = {}
        for name, value in table.items():
            if name == "joints":
                if not isinstance(value, list) or not value \
                        or not all(isinstance(j, str) for j in value):
                    raise ConfigError(f"springs.{group}.joints = {value!r}; expected a "
                                      "non-empty list of joint names")
                joints[group] = tuple(value)
                continue
            si, convert = PAPER_UNIT_PARAMETERS.get(name, (name, None))
            if si not in SPRING_PARAMETERS:
                raise UnknownNameError("spring parameter", name,
                                       (*SPRING_PARAMETERS, *PAPER_UNIT_PARAMETERS, "joints"))
            if si in params:
                raise ConfigError(f"springs.{group}: {si} given twice (SI and paper units)")
            v = axis_values(f"springs.{group}.{name}", value)
            if convert is not None:
                v = tuple(float(convert(x)) for x in v) if isinstance(v, tuple) \
                    else float(convert(v))
            params[si] = v
        springs[group] = params
    return springs, joints


__all__ = ["GAIT_PARAMETERS", "PAPER_UNIT_PARAMETERS", "gait_table", "spring_tables",
           "sweep_table"]
