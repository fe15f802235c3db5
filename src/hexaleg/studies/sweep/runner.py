"""Stiffness and spring-placement sweeps and optimisation over the whole robot.

The paper chooses one stiffness for one joint (k_M by eq. 19, k_E by minimising the energy of
eq. 21) and leaves "the appropriate elastic joint assembly position and the optimal stiffness" as
future work. This module answers that for a gait and a motor: which joints should carry a
dead-zone spring (eq. 8, :class:`hexaleg.robot.springs.DeadZoneSpring`), with which contact angles
and which stiffness.

Data flow
---------
A *point* is (gait parameters, spring design per joint group). A *group* is a joint class
(``"femur"``: the same design on all six femurs — left/right symmetric), one joint, or any list
of joints. A design gives, in SI (see :data:`SPRING_PARAMETERS`):

* ``k`` (N·m/rad) and optionally ``k_minus`` (k⁻, default k);
* the dead zone: ``theta_k`` (±θ_k, rad, > 0), or ``dead_zone`` (θ_k as a fraction of each
  joint's half range of motion in the gait, in (0, 1)), or ``theta_minus`` < ``theta_plus`` (rad);
* ``offset`` (rad): the spring's neutral relative to the *centre of each joint's range of motion
  in the gait* (default 0: a "centred" design, the symmetric dead zone about the motion that the
  paper assumes, eq. 8 and eq. 25).

Points sharing a gait share one :func:`hexaleg.dynamics.prepare.prepare`. Workers never receive
Pinocchio objects: a task carries a small picklable :class:`RunSpec` (robot files, motor name, force
objective, contact settings) and the gait parameters, and each worker keeps an :class:`Evaluator`
per gait in a small cache. A design then costs one force solve
(:meth:`hexaleg.dynamics.prepare.Prepared.solve`) and the energy metrics; the spring torques come
from the spring's torque basis (linear in k⁺ and k⁻), cached per dead-zone geometry.

Metric and objective
--------------------
Forces are distributed by the core's default objective ``"joule"`` (the convex quadratic program
with the fast exact path). Designs are ranked by :data:`DEFAULT_METRIC` = ``"electrical"``, the
energy the servos draw over a cycle (Joule loss plus mechanical work through the gearbox, no
regeneration unless the motor model allows it) — what the battery pays, i.e. the paper's energy
criterion (eq. 20–24) with a motor model. Any key of ``Analysis.metrics["total"]``
(:data:`METRICS`) may be chosen instead.

Results are a tidy :class:`pandas.DataFrame`, one row per point, written incrementally by
:class:`hexaleg.studies.sweep.store.ResultStore`; executors come from
:mod:`hexaleg.studies.sweep.executors`. See ``docs/sweep.md``.
"""

from __future__ import annotations

import dataclasses
import itertools
import math
import platform
import sys
from collections import OrderedDict
from collections.abc import Callable, Iterator, Mapping, Sequence
from concurrent.futures import FIRST_COMPLETED, Future, wait
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from hexaleg.config import from_mapping, load_toml
from hexaleg.design.rules import joint_range
from hexaleg.dynamics.energy import ENERGY_KEYS, NO_SAVING_KEYS, TORQUE_KEYS, savings
from hexaleg.dynamics.forces import ContactParams, check_objective
from hexaleg.dynamics.prepare import Prepared, prepare
from hexaleg.errors import (
    ConfigError,
    InfeasibleForcesError,
    InvalidParameterError,
    TorqueLimitError,
    UnknownNameError,
)
from hexaleg.motion.gait import GaitParams, tripod_gait
from hexaleg.robot.model import Robot, load_robot
from hexaleg.robot.motor import DEFAULT_MOTOR
from hexaleg.robot.motor import motor as motor_by_name
from hexaleg.robot.springs import DeadZoneSpring, SpringSet
from hexaleg.studies.sweep.executors import default_workers, open_executor
from hexaleg.studies.sweep.store import ResultStore
from hexaleg.units import deg_to_rad, nmm_per_deg_to_nm_per_rad

if TYPE_CHECKING:  # pandas is imported where tables are made: `import hexaleg` stays light
    import pandas as pd

METRICS: tuple[str, ...] = (*ENERGY_KEYS, "electrical_bus", *TORQUE_KEYS)
"""Keys of ``Analysis.metrics["total"]`` a sweep records and may optimise (J or N·m)."""
SAVING_METRICS: tuple[str, ...] = tuple(m for m in METRICS if m not in NO_SAVING_KEYS)
"""Metrics with a saving column (``saving.<key>``; the signed net work has none)."""
DEFAULT_METRIC = "electrical"
"""Metric ranked and optimised by default (energy drawn by the servos per cycle, J)."""

SPRING_PARAMETERS: tuple[str, ...] = ("k", "k_minus", "theta_k", "dead_zone", "theta_minus",
                                      "theta_plus", "offset")
"""Design parameters of a spring group, SI: N·m/rad, N·m/rad, rad, 1, rad, rad, rad."""
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
"""Scalar :class:`hexaleg.motion.gait.GaitParams` fields a sweep may fix or vary."""
LAYOUTS: tuple[str, ...] = ("product", "each")
"""How spring groups combine: every combination of all groups' values, or one group at a time."""
SECTIONS: tuple[str, ...] = ("sweep", "gait", "springs", "contact")
"""Top-level tables of a sweep spec file."""
CACHE_SIZE = 4
"""Gaits whose :class:`Evaluator` a worker keeps."""

Design = Mapping[str, Mapping[str, float]]
"""Spring design: group name → parameter → value (SI, :data:`SPRING_PARAMETERS`)."""


# --------------------------------------------------------------------------- specs


@dataclass(frozen=True)
class RunSpec:
    """What a worker needs to rebuild the analysis of a gait: small and picklable.

    Attributes:
        urdf: URDF file, or None for the built-in hexaleg robot.
        srdf: SRDF file, or None (the built-in one with the built-in robot).
        motor: Catalogue name of the servo on every joint (:data:`hexaleg.robot.motor.CATALOGUE`).
        objective: Force-distribution objective (:data:`hexaleg.dynamics.forces.OBJECTIVES`).
        contact: Contact settings.

    Raises:
        UnknownNameError: unknown motor. InvalidParameterError: unknown objective.
    """

    urdf: str | None = None
    srdf: str | None = None
    motor: str = DEFAULT_MOTOR
    objective: str = "joule"
    contact: ContactParams = field(default_factory=ContactParams)

    def __post_init__(self) -> None:
        motor_by_name(self.motor)
        check_objective(self.objective)

    def robot(self) -> Robot:
        """The robot, loaded from the URDF/SRDF (cached per process)."""
        return _robot(self.urdf, self.srdf)


def _values(name: str, value: Any) -> tuple[float, ...] | float:
    """A scalar (fixed), a list, or a range table ``{start, stop, num, scale}`` → values."""
    if isinstance(value, Mapping):
        allowed = ("start", "stop", "num", "scale")
        for key in value:
            if key not in allowed:
                raise UnknownNameError(f"range key of {name}", key, allowed)
        try:
            start, stop, num = float(value["start"]), float(value["stop"]), value["num"]
        except KeyError as e:
            raise ConfigError(f"{name}: a range needs start, stop and num; missing {e}") from None
        except (TypeError, ValueError):
            raise ConfigError(f"{name} = {value!r}: start and stop must be numbers") from None
        scale = value.get("scale", "linear")
        return _range(name, start, stop, num, scale)
    if isinstance(value, (list, tuple)):
        if not value:
            raise InvalidParameterError(name, [], "a non-empty list of values (an empty grid "
                                        "has no points)")
        return tuple(_number(f"{name}[{i}]", v) for i, v in enumerate(value))
    return _number(name, value)


def _number(name: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise ConfigError(f"{name} = {value!r} has type {type(value).__name__}; expected a "
                          "number, a list of numbers or a range table")
    if not math.isfinite(value):
        raise InvalidParameterError(name, value, "a finite number")
    return float(value)


def _range(name: str, start: float, stop: float, num: Any, scale: str = "linear"
           ) -> tuple[float, ...]:
    if isinstance(num, bool) or not isinstance(num, (int, np.integer)) or num < 1:
        raise InvalidParameterError(f"{name}.num", num, "an integer ≥ 1 (an empty grid has no "
                                    "points)")
    if scale not in ("linear", "log"):
        raise InvalidParameterError(f"{name}.scale", scale, "linear or log")
    for end, v in (("start", start), ("stop", stop)):
        if not math.isfinite(v) or (scale == "log" and v <= 0):
            raise InvalidParameterError(f"{name}.{end}", v,
                                        "a finite number" + (" > 0 for a log range"
                                                             if scale == "log" else ""))
    grid = np.geomspace(start, stop, num) if scale == "log" else np.linspace(start, stop, num)
    return tuple(float(x) for x in grid)


def parse_range(name: str, text: str) -> tuple[float, ...] | float:
    """Command-line values: ``"0.5"``, ``"0.1,0.2,0.4"``, ``"start:stop:num"`` or ``"…:log"``.

    Raises:
        InvalidParameterError: not numbers, or an empty range.
    """
    try:
        if ":" in text:
            parts = text.split(":")
            if len(parts) not in (3, 4):
                raise ValueError(text)
            scale = parts[3] if len(parts) == 4 else "linear"
            return _range(name, float(parts[0]), float(parts[1]), int(parts[2]), scale)
        if "," in text:
            return _values(name, [float(x) for x in text.split(",") if x.strip()])
        return _number(name, float(text))
    except ValueError:
        raise InvalidParameterError(name, text, "a number, comma-separated numbers, or "
                                    "start:stop:num[:log]") from None


def _check_spring_value(name: str, param: str, values: Sequence[float]) -> None:
    lo, hi = min(values), max(values)
    if param in ("k", "k_minus") and lo < 0:
        raise InvalidParameterError(name, lo, "≥ 0 (N·m/rad)")
    if param == "theta_k" and lo <= 0:  # θ⁻ < θ⁺ (eq. 8 with a dead zone of positive width)
        raise InvalidParameterError(name, lo, "> 0 (rad)")
    if param == "dead_zone" and not (lo > 0 and hi < 1):
        raise InvalidParameterError(name, lo if lo <= 0 else hi,
                                    "a fraction of the half range of motion in (0, 1)")


@dataclass(frozen=True)
class SweepSpec:
    """A sweep: fixed and varied gait parameters, spring groups and their designs.

    Attributes:
        run: Robot, motor, force objective and contact settings.
        gait: Gait parameters, :data:`GAIT_PARAMETERS` → a value (fixed) or a tuple (an axis).
        springs: Group → (parameter → value or tuple of values), SI, :data:`SPRING_PARAMETERS`.
        joints: Group → explicit joint names; groups not listed are a joint class or one joint
            (``Robot.joints(group)``).
        layout: ``"product"`` (all combinations of every axis) or ``"each"`` (one sprung group
            per point: the product of that group's axes, the other groups without springs).
        metric: Metric the summary ranks by (:data:`METRICS`).
        chunk_size: Points per task and per part file (does not change the results).

    Raises:
        UnknownNameError: an unknown gait or spring parameter, metric or layout (lists the
            valid ones).
        InvalidParameterError: an empty grid, a value out of range, a group without ``k`` or
            without exactly one dead-zone choice.
    """

    run: RunSpec = field(default_factory=RunSpec)
    gait: Mapping[str, float | tuple[float, ...]] = field(default_factory=dict)
    springs: Mapping[str, Mapping[str, float | tuple[float, ...]]] = field(default_factory=dict)
    joints: Mapping[str, tuple[str, ...]] = field(default_factory=dict)
    layout: str = "product"
    metric: str = DEFAULT_METRIC
    chunk_size: int = 50

    def __post_init__(self) -> None:
        for name in self.gait:
            if name not in GAIT_PARAMETERS:
                raise UnknownNameError("gait parameter", name, GAIT_PARAMETERS)
        for group, params in self.springs.items():
            self._check_group(group, params)
        for group in self.joints:
            if group not in self.springs:
                raise UnknownNameError("spring group", group, self.springs)
        if self.layout not in LAYOUTS:
            raise UnknownNameError("layout", self.layout, LAYOUTS)
        if self.metric not in METRICS:
            raise UnknownNameError("metric", self.metric, METRICS)
        if isinstance(self.chunk_size, bool) or not isinstance(self.chunk_size, int) \
                or self.chunk_size < 1:
            raise InvalidParameterError("chunk_size", self.chunk_size, "an integer ≥ 1")
        for g in self.gaits():  # every gait of the grid is valid (GaitParams checks ranges)
            GaitParams(**g)

    @staticmethod
    def _check_group(group: str, params: Mapping[str, Any]) -> None:
        for name, value in params.items():
            if name not in SPRING_PARAMETERS:
                raise UnknownNameError("spring parameter", name,
                                       (*SPRING_PARAMETERS, *PAPER_UNIT_PARAMETERS, "joints"))
            values = value if isinstance(value, tuple) else (value,)
            if not values:
                raise InvalidParameterError(f"{group}.{name}", [], "a non-empty list of values")
            _check_spring_value(f"{group}.{name}", name, values)
        if "k" not in params:
            raise InvalidParameterError(f"{group}.k", None, "a stiffness (N·m/rad), or "
                                        "k_nmm_per_deg")
        choices = [c for c in (("theta_k",), ("dead_zone",), ("theta_minus", "theta_plus"))
                   if any(p in params for p in c)]
        if len(choices) != 1 or not all(p in params for p in choices[0]):
            raise InvalidParameterError(f"{group} dead zone", sorted(params),
                                        "exactly one of theta_k, dead_zone, or theta_minus with "
                                        "theta_plus")
        if "theta_minus" in params:
            tm, tp = (params[p] if isinstance(params[p], tuple) else (params[p],)
                      for p in ("theta_minus", "theta_plus"))
            if max(tm) >= min(tp):
                raise InvalidParameterError(f"{group}.theta_minus", max(tm),
                                            f"< every {group}.theta_plus (min {min(tp)})")

    @classmethod
    def from_mapping(cls, data: Mapping[str, Any], where: str = "sweep spec") -> SweepSpec:
        """A spec from parsed TOML (see ``docs/sweep.md``).

        ``[sweep]`` holds ``metric``, ``layout``, ``chunk_size`` and the :class:`RunSpec` keys
        ``urdf``, ``srdf``, ``motor``, ``objective``; ``[contact]`` the
        :class:`~hexaleg.dynamics.forces.ContactParams`; ``[gait]`` gait parameters;
        ``[springs.<group>]`` one table per group with an optional ``joints`` list. A scalar is
        fixed, a list or a range table ``{start, stop, num, scale = "linear" | "log"}`` is an axis.
        Keys in the paper's units (:data:`PAPER_UNIT_PARAMETERS`) are converted to SI through
        :mod:`hexaleg.units`.

        Raises:
            UnknownNameError: unknown table or key (lists the valid ones).
            ConfigError: a value of the wrong type.
            InvalidParameterError: an empty grid or a value out of range.
        """
        for name in data:
            if name not in SECTIONS:
                raise UnknownNameError(f"table in {where}", name, SECTIONS)
        sweep = dict(data.get("sweep", {}))
        run_keys = {"urdf", "srdf", "motor", "objective"}
        run_table = {k: sweep.pop(k) for k in list(sweep) if k in run_keys}
        contact = from_mapping(ContactParams, data.get("contact", {}), f"{where} [contact]")
        run = RunSpec(**{k: _string(f"sweep.{k}", v) for k, v in run_table.items()},
                      contact=contact)
        allowed = ("metric", "layout", "chunk_size")
        for key in sweep:
            if key not in allowed:
                raise UnknownNameError(f"key in {where} [sweep]", key, (*allowed, *run_keys))
        gait_table = data.get("gait", {})
        gait = {}
        for name, value in gait_table.items():
            if name not in GAIT_PARAMETERS:
                raise UnknownNameError("gait parameter", name, GAIT_PARAMETERS)
            v = _values(f"gait.{name}", value)
            if name == "samples":
                v = tuple(int(x) for x in v) if isinstance(v, tuple) else int(v)
            gait[name] = v
        springs, joints = {}, {}
        for group, table in data.get("springs", {}).items():
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
                v = _values(f"springs.{group}.{name}", value)
                if convert is not None:
                    v = tuple(float(convert(x)) for x in v) if isinstance(v, tuple) \
                        else float(convert(v))
                params[si] = v
            springs[group] = params
        return cls(run=run, gait=gait, springs=springs, joints=joints, **sweep)

    @classmethod
    def from_toml(cls, path: str | Path) -> SweepSpec:
        """A spec from a TOML file (see :meth:`from_mapping`)."""
        return cls.from_mapping(load_toml(path), str(path))

    # -- the grid

    def _axes(self, params: Mapping[str, Any]) -> list[tuple[str, tuple]]:
        return [(k, v) for k, v in params.items() if isinstance(v, tuple)]

    def gaits(self) -> list[dict[str, Any]]:
        """Every gait of the grid as :class:`~hexaleg.motion.gait.GaitParams` keyword arguments."""
        fixed = {k: v for k, v in self.gait.items() if not isinstance(v, tuple)}
        axes = self._axes(self.gait)
        return [{**fixed, **dict(zip([a for a, _ in axes], combo, strict=True))}
                for combo in itertools.product(*(vals for _, vals in axes))]

    def designs(self) -> list[dict[str, dict[str, float]]]:
        """Every spring design of the grid, in point order within one gait."""
        def group_designs(group: str) -> list[dict[str, float]]:
            params = self.springs[group]
            fixed = {k: v for k, v in params.items() if not isinstance(v, tuple)}
            axes = self._axes(params)
            return [{**fixed, **dict(zip([a for a, _ in axes], combo, strict=True))}
                    for combo in itertools.product(*(vals for _, vals in axes))]

        if not self.springs:
            return [{}]
        per_group = {g: group_designs(g) for g in self.springs}
        if self.layout == "each":
            return [{g: d} for g in self.springs for d in per_group[g]]
        return [dict(zip(per_group, combo, strict=True))
                for combo in itertools.product(*per_group.values())]

    @property
    def n_points(self) -> int:
        """Number of points: gaits × designs."""
        return len(self.gaits()) * len(self.designs())

    def groups(self, robot: Robot) -> dict[str, tuple[str, ...]]:
        """Group → joints on ``robot``.

        Raises:
            UnknownNameError: a group is neither a joint class nor a joint, or lists a joint the
                robot does not have (the message lists classes and joints).
            InvalidParameterError: a joint is in two groups.
        """
        out: dict[str, tuple[str, ...]] = {}
        seen: dict[str, str] = {}
        for group in self.springs:
            joints = self.joints.get(group)
            if joints is None:
                joints = robot.joints(group)
            for j in joints:
                robot.column(j)
                if j in seen:
                    raise InvalidParameterError(f"joint {j}", f"in groups {seen[j]} and {group}",
                                                "each joint in at most one spring group")
                seen[j] = group
            out[group] = tuple(joints)
        return out

    def to_dict(self) -> dict[str, Any]:
        """The spec as plain JSON-able data (identifies the sweep in a store's manifest)."""
        def plain(v: Any) -> Any:
            return list(v) if isinstance(v, tuple) else v

        return {
            "run": {"urdf": self.run.urdf, "srdf": self.run.srdf, "motor": self.run.motor,
                    "objective": self.run.objective,
                    "contact": dataclasses.asdict(self.run.contact)},
            "gait": {k: plain(v) for k, v in self.gait.items()},
            "springs": {g: {k: plain(v) for k, v in p.items()} for g, p in self.springs.items()},
            "joints": {g: list(j) for g, j in self.joints.items()},
            "layout": self.layout,
        }


def _string(name: str, value: Any) -> str:
    if not isinstance(value, str):
        raise ConfigError(f"{name} = {value!r} has type {type(value).__name__}; expected a string")
    return value


# --------------------------------------------------------------------------- evaluation


_ROBOTS: dict[tuple[str | None, str | None], Robot] = {}
_EVALUATORS: OrderedDict[tuple, Evaluator] = OrderedDict()


def _robot(urdf: str | None, srdf: str | None) -> Robot:
    if (urdf, srdf) not in _ROBOTS:
        _ROBOTS[urdf, srdf] = load_robot(urdf, srdf)
    return _ROBOTS[urdf, srdf]


def clear_cache() -> None:
    """Forget the robots and evaluators this process has built (e.g. after editing a URDF, or
    to time a sweep from a cold start)."""
    _ROBOTS.clear()
    _EVALUATORS.clear()


def evaluator(run: RunSpec, gait: Mapping[str, Any]) -> Evaluator:
    """The :class:`Evaluator` of ``gait``, built once per process and kept in a small cache.

    Args:
        run: Robot, motor, objective and contact settings.
        gait: :class:`~hexaleg.motion.gait.GaitParams` keyword arguments.
    """
    key = (run, tuple(sorted(gait.items())))
    if key in _EVALUATORS:
        _EVALUATORS.move_to_end(key)
        return _EVALUATORS[key]
    ev = Evaluator(run, GaitParams(**gait))
    _EVALUATORS[key] = ev
    while len(_EVALUATORS) > CACHE_SIZE:
        _EVALUATORS.popitem(last=False)
    return ev


class Evaluator:
    """Metrics of spring designs on one gait: ``prepare`` once, one force solve per design.

    Args:
        run: Robot, motor, force objective, contact settings.
        gait: The gait.

    Attributes:
        robot: The robot. motion: The gait's motion. prepared: Its
            :class:`~hexaleg.dynamics.prepare.Prepared`. baseline: Metrics without springs.
        centre: Joint → centre of its range of motion in the gait, rad.
        half_range: Joint → half its range of motion in the gait, rad.
        evaluations: Designs evaluated so far (for tests and benchmarks).
    """

    def __init__(self, run: RunSpec, gait: GaitParams) -> None:
        self.run = run
        self.gait = gait
        self.robot = run.robot()
        self.motion = tripod_gait(self.robot, gait)
        self.prepared: Prepared = prepare(self.robot, self.motion, motor=run.motor,
                                          contact=run.contact)
        self.baseline = self.prepared.baseline(run.objective)
        ranges = {j: joint_range(self.robot, self.motion, j) for j in self.robot.joint_names}
        self.centre = {j: (lo + hi) / 2 for j, (lo, hi) in ranges.items()}
        self.half_range = {j: (hi - lo) / 2 for j, (lo, hi) in ranges.items()}
        self.evaluations = 0
        self._basis: OrderedDict[tuple, tuple[np.ndarray, np.ndarray]] = OrderedDict()

    def spring(self, joint: str, params: Mapping[str, float]) -> DeadZoneSpring:
        """The spring of design ``params`` on ``joint``, with its absolute neutral angle (SI).

        Raises:
            InvalidParameterError: an out-of-range parameter (from
                :class:`~hexaleg.robot.springs.DeadZoneSpring`).
        """
        theta_k = params.get("theta_k")
        if "dead_zone" in params:
            theta_k = params["dead_zone"] * self.half_range[joint]
        return DeadZoneSpring(stiffness=params["k"], theta_k=theta_k,
                              theta_minus=params.get("theta_minus"),
                              theta_plus=params.get("theta_plus"),
                              stiffness_minus=params.get("k_minus"),
                              neutral=self.centre[joint] + params.get("offset", 0.0))

    def springs(self, groups: Mapping[str, Sequence[str]], design: Design) -> SpringSet:
        """The springs of ``design`` on every joint of its groups (absolute neutrals, SI)."""
        return SpringSet({j: self.spring(j, params) for g, params in design.items()
                          for j in groups[g]})

    def _unit_torques(self, joints: Sequence[str], params: Mapping[str, float]
                      ) -> tuple[np.ndarray, np.ndarray]:
        """Torques (T, nj) per unit k⁺ and per unit k⁻ of a group's dead-zone geometry."""
        geometry = tuple(sorted((k, v) for k, v in params.items() if k not in ("k", "k_minus")))
        key = (tuple(joints), geometry)
        if key not in self._basis:
            geo = dict(geometry)
            q, v = self.motion.q, self.motion.v
            plus = SpringSet({j: self.spring(j, {**geo, "k": 1.0, "k_minus": 0.0})
                              for j in joints}).torques(self.robot, q, v)
            minus = SpringSet({j: self.spring(j, {**geo, "k": 0.0, "k_minus": 1.0})
                               for j in joints}).torques(self.robot, q, v)
            self._basis[key] = (plus, minus)
            while len(self._basis) > 64:
                self._basis.popitem(last=False)
        self._basis.move_to_end(key)
        return self._basis[key]

    def spring_torques(self, groups: Mapping[str, Sequence[str]], design: Design) -> np.ndarray:
        """Spring torques of ``design`` along the gait, shape (T, nj), N·m.

        Equal to ``self.springs(groups, design).torques(robot, q, v)``, through the spring's
        torque basis (linear in k⁺ and k⁻ for a fixed dead zone), cached per dead zone.
        """
        tau = np.zeros_like(self.prepared.q)
        for g, params in design.items():
            self.springs({g: groups[g]}, {g: params})  # validates the design
            plus, minus = self._unit_torques(groups[g], params)
            k = params["k"]
            k_minus = params.get("k_minus", k)
            tau += k * plus + k_minus * minus
        return tau

    def metrics(self, groups: Mapping[str, Sequence[str]], design: Design) -> dict[str, Any]:
        """Energy metrics of the gait with ``design``, as :func:`hexaleg.dynamics.energy.metrics`.

        Raises:
            InfeasibleForcesError, TorqueLimitError: no admissible forces or torques.
        """
        self.evaluations += 1
        tau_s = self.spring_torques(groups, design)
        _, tau_m, _ = self.prepared.solve(tau_s, self.run.objective)
        return self.prepared.metrics(tau_m)

    def value(self, groups: Mapping[str, Sequence[str]], design: Design,
              metric: str = DEFAULT_METRIC) -> float:
        """One metric total of ``design`` (J or N·m); +inf when no forces or torques exist."""
        try:
            return float(self.metrics(groups, design)["total"][metric])
        except (InfeasibleForcesError, TorqueLimitError):
            return math.inf

    def row(self, groups: Mapping[str, Sequence[str]], design: Design) -> dict[str, Any]:
        """Every metric total, its baseline and its saving for ``design``, plus a status.

        Returns:
            ``{<metric>: …, "baseline.<metric>": …, "saving.<metric>": …, "status": "ok"}``;
            a design with no admissible forces or torques has ``status`` = the error message
            and NaN metrics and savings (its baselines stay).
        """
        out: dict[str, Any] = {}
        try:
            m = self.metrics(groups, design)
            s = savings(m, self.baseline)
            status = "ok"
        except (InfeasibleForcesError, TorqueLimitError) as e:
            m = {"total": dict.fromkeys(METRICS, math.nan)}
            s = {"total": dict.fromkeys(SAVING_METRICS, math.nan)}
            status = f"{type(e).__name__}: {e}"
        for key in METRICS:
            out[key] = m["total"][key]
        for key in METRICS:
            out[f"baseline.{key}"] = self.baseline["total"][key]
        for key in SAVING_METRICS:
            out[f"saving.{key}"] = s["total"][key]
        out["status"] = status
        return out


def evaluate_chunk(run: RunSpec, gait: Mapping[str, Any], groups: Mapping[str, Sequence[str]],
                   points: Sequence[tuple[int, Design]]) -> pd.DataFrame:
    """Rows of a chunk of points sharing one gait (the task a worker runs).

    Args:
        run: Robot, motor, objective, contact (picklable; the worker rebuilds the robot).
        gait: GaitParams keyword arguments.
        groups: Group → joint names.
        points: (point index, design) pairs.

    Returns:
        One row per point: ``point``, the gait parameters (``gait.<name>``), the design
        (``<group>.<parameter>``, NaN for a group without a spring at that point, see
        ``springs``), ``springs`` (the sprung groups joined by ``+``, or ``none``), then
        :meth:`Evaluator.row`.
    """
    import pandas as pd

    ev = evaluator(run, gait)
    full = dataclasses.asdict(ev.gait)
    rows = []
    for index, design in points:
        row: dict[str, Any] = {"point": index}
        for name in GAIT_PARAMETERS:
            value = full[name]
            row[f"gait.{name}"] = math.nan if value is None else value
        row["springs"] = "+".join(design) or "none"
        row.update(_design_columns(groups, design))
        row.update(ev.row(groups, design))
        rows.append(row)
    return pd.DataFrame(rows)


def _design_columns(groups: Mapping[str, Sequence[str]], design: Design) -> dict[str, float]:
    """``<group>.<parameter>`` columns; defaults filled in (k⁻ = k, offset 0), NaN for a dead-zone
    form the design does not use and for every parameter of a group without a spring."""
    out = {}
    for g in groups:
        params = dict(design.get(g, {}))
        if params:
            params.setdefault("k_minus", params["k"])
            params.setdefault("offset", 0.0)
        for p in SPRING_PARAMETERS:
            out[f"{g}.{p}"] = float(params[p]) if p in params else math.nan
    return out


# --------------------------------------------------------------------------- running sweeps


@dataclass
class SweepResult:
    """The outcome of :func:`run_sweep`.

    Attributes:
        table: One row per point, sorted by ``point``.
        directory: Where the parts and manifest are.
        computed: Points evaluated by this call.
        reused: Points found finished on disk and not recomputed.
    """

    table: pd.DataFrame
    directory: Path
    computed: int
    reused: int


def software_versions() -> dict[str, str]:
    """Versions of Python and the libraries a sweep's numbers depend on."""
    import pandas as pd
    import pinocchio
    import scipy

    from hexaleg import __version__

    return {"hexaleg": __version__, "python": platform.python_version(),
            "pinocchio": pinocchio.__version__, "numpy": np.__version__,
            "scipy": scipy.__version__, "pandas": pd.__version__}


def _chunks(spec: SweepSpec, todo: Sequence[int]) -> Iterator[tuple[dict, list[int]]]:
    """Unfinished points grouped by gait, at most ``chunk_size`` per chunk."""
    gaits, n_designs = spec.gaits(), len(spec.designs())
    for gi, points in itertools.groupby(todo, key=lambda i: i // n_designs):
        block = list(points)
        for start in range(0, len(block), spec.chunk_size):
            yield gaits[gi], block[start:start + spec.chunk_size]


def run_sweep(spec: SweepSpec, out: str | Path, *, executor: str = "process",
              workers: int | None = None, scheduler: str | None = None,
              progress: bool = False,
              on_chunk: Callable[[pd.DataFrame], None] | None = None) -> SweepResult:
    """Evaluate every point of ``spec``, writing rows to ``out`` as chunks finish; resumable.

    Points already on disk (a sweep killed earlier with the same spec) are not recomputed.

    Args:
        spec: The sweep.
        out: Output directory (manifest + Parquet parts,
            :class:`hexaleg.studies.sweep.store.ResultStore`).
        executor: ``"process"`` (local pool), ``"serial"`` or ``"dask"``
            (:func:`hexaleg.studies.sweep.executors.open_executor`).
        workers: Local pool size (default: the cores available).
        scheduler: Dask scheduler address (with ``executor="dask"``).
        progress: Show a tqdm progress bar on stderr.
        on_chunk: Called with each finished chunk's rows after they are on disk.

    Returns:
        The full table and counts of computed and reused points.

    Raises:
        UnknownNameError: a group that is neither a joint class nor a joint (lists them).
        ConfigError: ``out`` holds a different sweep (names the differences).
        ExecutorError: the Dask scheduler cannot be reached (nothing is computed or lost).
        OutputError: results cannot be written.
    """
    robot = spec.run.robot()
    groups = spec.groups(robot)
    metadata = {
        "robot": {"name": robot.name, "urdf": str(robot.urdf_path), "nq": robot.model.nq,
                  "nv": robot.model.nv, "mass_kg": robot.mass, "groups": groups},
        "motor": spec.run.motor,
        "gaits": spec.gaits(),
        "n_points": spec.n_points,
        "versions": software_versions(),
    }
    store = ResultStore(out, spec.to_dict(), metadata)
    done = store.finished()
    designs = spec.designs()
    todo = [i for i in range(spec.n_points) if i not in done]
    tasks = ((gait, [(i, designs[i % len(designs)]) for i in block])
             for gait, block in _chunks(spec, todo))
    # Chunks in flight: enough to keep every worker busy, few enough that an interrupted sweep
    # has computed little that is not on disk yet.
    window = {"serial": 1, "process": 2 * (workers or default_workers())}.get(executor, 64)
    if executor == "process" and todo:
        # Forked workers inherit this process's evaluator cache: build the first gait's
        # evaluator (gait, prepare, baseline) once here instead of once in every worker.
        evaluator(spec.run, spec.gaits()[todo[0] // len(designs)])
    bar = None
    computed = 0
    with open_executor(executor, workers=workers, scheduler=scheduler) as ex:
        pending: set[Future] = set()

        def refill() -> None:
            for gait, points in itertools.islice(tasks, window - len(pending)):
                pending.add(ex.submit(evaluate_chunk, spec.run, gait, groups, points))

        refill()
        if progress and todo:  # after the pool has started: tqdm runs a monitor thread
            from tqdm import tqdm

            bar = tqdm(total=len(todo), file=sys.stderr, unit="pt", desc="sweep")
        try:
            while pending:
                finished, _ = wait(pending, return_when=FIRST_COMPLETED)
                pending -= finished
                refill()
                # a failed chunk first (it raises), then the others in point order
                for fut in sorted(finished, key=lambda f: -1 if f.exception() is not None
                                  else int(f.result()["point"].iloc[0])):
                    rows = fut.result()
                    store.write(rows)
                    computed += len(rows)
                    if bar is not None:
                        bar.update(len(rows))
                    if on_chunk is not None:
                        on_chunk(rows)
        finally:
            for fut in pending:
                fut.cancel()
            if bar is not None:
                bar.close()
    return SweepResult(table=store.table(), directory=store.directory, computed=computed,
                       reused=len(done))


def summary(table: pd.DataFrame, metric: str = DEFAULT_METRIC) -> str:
    """A text summary of a sweep table: the best point (lowest ``metric``) per sprung-group set.

    Raises:
        UnknownNameError: ``metric`` is not a column of the table.
    """
    import pandas as pd

    if metric not in table.columns:
        raise UnknownNameError("metric", metric, [m for m in METRICS if m in table.columns])
    ok = table[table["status"] == "ok"]
    lines = [f"{len(table)} points, {len(ok)} evaluated without error; best {metric} "
             "(lower is better) per sprung-group set:"]
    # the inputs: design columns, and the gait parameters the sweep varies
    inputs = [c for c in table.columns if "." in c and not c.startswith(("baseline.", "saving."))
              and (not c.startswith("gait.") or table[c].nunique() > 1)]
    for springs, rows in ok.groupby("springs", sort=False):
        best = rows.loc[rows[metric].idxmin()]
        params = ", ".join(f"{c} = {best[c]:.4g}" for c in inputs if not pd.isna(best[c]))
        lines.append(f"  {springs}: {metric} = {best[metric]:.6g} (no springs "
                     f"{best['baseline.' + metric]:.6g}), saving "
                     f"{100 * best['saving.' + metric]:+.2f} % at point {int(best['point'])}: "
                     f"{params}")
    return "\n".join(lines)


# --------------------------------------------------------------------------- optimisation


@dataclass(frozen=True)
class Optimum:
    """The optimal (k, θ_k[, offset]) of one spring group for one metric on one gait.

    Attributes:
        group: Group name. joints: Its joints. metric: The metric minimised.
        k: Stiffness, N·m/rad. theta_k: Symmetric contact angle, rad. offset: Neutral offset
            from the centre of each joint's range of motion, rad (fixed or optimised).
        value: The metric at the optimum (J or N·m). baseline: The metric without springs.
        saving: ``(baseline − value) / |baseline|``.
        grid_value: The best value of the starting grid. evaluations: Designs evaluated.
    """

    group: str
    joints: tuple[str, ...]
    metric: str
    k: float
    theta_k: float
    offset: float
    value: float
    baseline: float
    saving: float
    grid_value: float
    evaluations: int

    def design(self) -> dict[str, float]:
        """The group's design parameters (``k``, ``theta_k``, ``offset``)."""
        return {"k": self.k, "theta_k": self.theta_k, "offset": self.offset}


def optimise(ev: Evaluator, group: str, joints: Sequence[str], metric: str = DEFAULT_METRIC, *,
             k_bounds: tuple[float, float] = (1e-3, 3.0),
             theta_bounds: tuple[float, float] | None = None, offset: float = 0.0,
             offset_bounds: tuple[float, float] | None = None,
             grid: tuple[int, ...] = (12, 6, 5), start: Sequence[float] | None = None,
             tol: float = 1e-4) -> Optimum:
    """The (k, θ_k) — and optionally the neutral offset — minimising ``metric`` for one group.

    A symmetric dead-zone spring with the same design goes on every joint of the group. The
    objective is piecewise smooth in θ_k and the offset (samples enter and leave the engaged
    region) and k spans decades, so the search runs on (log k, θ_k[, offset]) scaled to the unit
    box: a grid start (or ``start``), then bounded Nelder–Mead (:func:`scipy.optimize.minimize`,
    derivative-free, tolerant of the kinks; scipy ≥ 1.7 supports bounds for it). Designs without
    admissible forces count as +inf.

    Args:
        ev: Evaluator of the gait.
        group: Group name (for the result). joints: The joints sprung with the same design.
        metric: A key of :data:`METRICS`.
        k_bounds: Stiffness bounds, N·m/rad, 0 < low < high.
        theta_bounds: θ_k bounds, rad, 0 < low < high; default (0.01, 0.95) × the largest half
            range of motion of ``joints`` in the gait.
        offset: Neutral offset from each joint's centre of motion, rad, when it is held fixed.
        offset_bounds: (low, high) rad to optimise the offset too (a preloaded spring that
            carries part of a steady load such as gravity); None holds it at ``offset``.
        grid: Starting grid points per variable (k log-spaced, θ_k and offset linear), each ≥ 2;
            the third entry is used only with ``offset_bounds``; ignored with ``start``.
        start: (k, θ_k[, offset]) to start from instead of the grid.
        tol: Convergence tolerance on the scaled variables.

    Returns:
        The optimum (never worse than the start).

    Raises:
        UnknownNameError: unknown metric. InvalidParameterError: bad bounds, grid or start.
    """
    from scipy.optimize import minimize

    if metric not in METRICS:
        raise UnknownNameError("metric", metric, METRICS)
    if theta_bounds is None:
        half = max(ev.half_range[j] for j in joints)
        theta_bounds = (0.01 * half, 0.95 * half)
    bounds = [k_bounds, theta_bounds] + ([offset_bounds] if offset_bounds is not None else [])
    for name, (lo, hi) in zip(("k_bounds", "theta_bounds", "offset_bounds"), bounds,
                              strict=False):
        lo, hi = _number(name, lo), _number(name, hi)
        if not lo < hi or (name != "offset_bounds" and lo <= 0):
            raise InvalidParameterError(name, (lo, hi), "low < high" + (
                "" if name == "offset_bounds" else ", low > 0"))
    dims = len(bounds)
    (lo_k, hi_k), (lo_t, hi_t) = bounds[0], bounds[1]
    groups = {group: tuple(joints)}
    count0 = ev.evaluations

    def unscale(x: np.ndarray) -> dict[str, float]:
        x = np.clip(x, 0.0, 1.0)
        design = {"k": float(lo_k * (hi_k / lo_k) ** x[0]),
                  "theta_k": float(lo_t + (hi_t - lo_t) * x[1]), "offset": offset}
        if dims == 3:
            lo_o, hi_o = bounds[2]
            design["offset"] = float(lo_o + (hi_o - lo_o) * x[2])
        return design

    def scale(values: Sequence[float]) -> np.ndarray:
        x = [math.log(values[0] / lo_k) / math.log(hi_k / lo_k), (values[1] - lo_t) / (hi_t - lo_t)]
        if dims == 3:
            x.append((values[2] - bounds[2][0]) / (bounds[2][1] - bounds[2][0]))
        return np.clip(np.array(x), 0.0, 1.0)

    def f(x: np.ndarray) -> float:
        return ev.value(groups, {group: unscale(x)}, metric)

    if start is None:
        n = tuple(grid[:dims])
        if len(n) != dims or any(isinstance(m, bool) or not isinstance(m, int) or m < 2
                                 for m in n):
            raise InvalidParameterError("grid", grid, f"{dims} integers ≥ 2")
        cands = [np.array(x) for x in itertools.product(*(np.linspace(0, 1, m) for m in n))]
        step = 1.0 / (np.array(n) - 1)
    else:
        if len(start) != dims or not all(v > 0 for v in start[:2]):
            raise InvalidParameterError("start", start, f"{dims} values, k > 0 and θ_k > 0")
        cands = [scale(start)]
        step = np.full(dims, 0.1)
    values = [f(x) for x in cands]
    x0, f0 = cands[int(np.argmin(values))], min(values)
    # initial simplex: one grid step along each variable, pointing into the box
    simplex = [x0] + [x0 + np.eye(dims)[d] * step[d] * (-1 if x0[d] > 0.5 else 1)
                      for d in range(dims)]
    res = minimize(f, x0, method="Nelder-Mead", bounds=[(0.0, 1.0)] * dims,
                   options={"initial_simplex": np.array(simplex), "xatol": tol, "fatol": 1e-12,
                            "maxiter": 200 * dims})
    x, value = (res.x, float(res.fun)) if res.fun <= f0 else (x0, f0)
    design = unscale(x)
    base = float(ev.baseline["total"][metric])
    return Optimum(group=group, joints=tuple(joints), metric=metric, k=design["k"],
                   theta_k=design["theta_k"], offset=design["offset"], value=value,
                   baseline=base, saving=(base - value) / abs(base) if base else 0.0,
                   grid_value=f0, evaluations=ev.evaluations - count0)


def placement(ev: Evaluator, groups: Mapping[str, Sequence[str]],
              metric: str = DEFAULT_METRIC, *,
              starts: Mapping[str, Sequence[float]] | None = None,
              **options: Any) -> tuple[dict[str, Optimum], pd.DataFrame]:
    """Which groups benefit from a spring: each group's optimum, then every combination.

    Each group is optimised alone (:func:`optimise`, others without springs); every combination
    of two or more groups is then evaluated with each group at its own optimum (not re-optimised
    jointly — the groups interact only through the shared foot forces).

    Args:
        ev: Evaluator of the gait.
        groups: Group → joints, e.g. ``{"coxa": robot.joints("coxa"), …}``.
        metric: A key of :data:`METRICS`.
        starts: Group → (k, θ_k[, offset]) to start from (e.g. a sweep's best point) instead of
            a grid.
        **options: More :func:`optimise` keyword arguments.

    Returns:
        (group → optimum, table with one row per set of sprung groups: ``springs``, ``value``,
        ``baseline``, ``saving``, ``benefits`` (saving > 0), sorted by saving, best first).
    """
    import pandas as pd

    starts = starts or {}
    optima = {g: optimise(ev, g, joints, metric, start=starts.get(g), **options)
              for g, joints in groups.items()}
    rows = []
    names = list(groups)
    base = float(ev.baseline["total"][metric])
    for r in range(1, len(names) + 1):
        for combo in itertools.combinations(names, r):
            design = {g: optima[g].design() for g in combo}
            value = optima[combo[0]].value if r == 1 else ev.value(groups, design, metric)
            rows.append({"springs": "+".join(combo), "value": value, "baseline": base,
                         "saving": (base - value) / abs(base) if base else 0.0,
                         **{f"{g}.{p}": v for g in combo for p, v in design[g].items()}})
    table = pd.DataFrame(rows).sort_values("saving", ascending=False, kind="stable")
    table["benefits"] = table["saving"] > 0
    return optima, table.reset_index(drop=True)


def robustness(run: RunSpec, gait: GaitParams, groups: Mapping[str, Sequence[str]],
               design: Design, metric: str = DEFAULT_METRIC, *,
               factors: Sequence[float] = (0.8, 0.9, 1.0, 1.1, 1.2),
               parameters: Sequence[str] = ("period", "stride_length")) -> pd.DataFrame:
    """Saving of a fixed design when the gait's period or amplitude changes.

    The design is frozen on the nominal gait — its neutral angles are absolute, taken from the
    nominal ranges of motion — as a built spring would be; only the gait changes.

    Args:
        run: Robot, motor, objective, contact.
        gait: The nominal gait (the design was chosen for it).
        groups: Group → joints.
        design: Group → parameters (e.g. ``{g: optimum.design()}``).
        metric: A key of :data:`METRICS`.
        factors: Multipliers of each parameter (1 = nominal), > 0.
        parameters: Gait parameters to vary, from ``period`` and ``stride_length`` (amplitude).

    Returns:
        One row per (parameter, factor): ``parameter``, ``factor``, ``gait value``, ``value``,
        ``baseline``, ``saving``, ``status``.

    Raises:
        UnknownNameError: a parameter other than period / stride_length.
        InvalidParameterError: a factor ≤ 0.
    """
    import pandas as pd

    for p in parameters:
        if p not in ("period", "stride_length"):
            raise UnknownNameError("robustness parameter", p, ("period", "stride_length"))
    for fct in factors:
        if not _number("factor", fct) > 0:
            raise InvalidParameterError("factor", fct, "> 0")
    nominal = evaluator(run, dataclasses.asdict(gait))
    springs = nominal.springs(groups, design)
    rows = []
    for p in parameters:
        for fct in factors:
            varied = dataclasses.replace(gait, **{p: getattr(gait, p) * fct})
            ev = evaluator(run, dataclasses.asdict(varied))
            base = float(ev.baseline["total"][metric])
            try:
                value = float(ev.prepared.evaluate(springs, run.objective)
                              .metrics["total"][metric])
                status = "ok"
            except (InfeasibleForcesError, TorqueLimitError) as e:
                value, status = math.nan, f"{type(e).__name__}: {e}"
            rows.append({"parameter": p, "factor": float(fct), "gait value": getattr(varied, p),
                         "value": value, "baseline": base,
                         "saving": (base - value) / abs(base) if base else 0.0,
                         "status": status})
    return pd.DataFrame(rows)
