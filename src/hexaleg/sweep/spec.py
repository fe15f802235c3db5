"""A sweep spec: fixed and varied gait parameters, spring groups and their designs, as a grid.

A *point* is (gait parameters, spring design per joint group); groups and design parameters are
those of :mod:`hexaleg.design.evaluator` (:data:`~hexaleg.design.evaluator.SPRING_PARAMETERS`,
SI). A spec comes from TOML (``[sweep]``, ``[contact]``, ``[gait]``, ``[springs.<group>]``, see
``docs/sweep.md``) or is built in Python; its grid is every gait × every design, gait points being
the outer loop so all designs of one gait are consecutive.
"""

from __future__ import annotations

import dataclasses
import itertools
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from hexaleg.checks import count, integer, named_arguments
from hexaleg.config import check_tables, load_toml
from hexaleg.design.evaluator import DEFAULT_METRIC, METRICS, SPRING_PARAMETERS
from hexaleg.design.search.optimal import OBJECTIVE_METRIC
from hexaleg.errors import ConfigError, InvalidParameterError, UnknownNameError
from hexaleg.robot.model import Robot
from hexaleg.scenario.scenario import Scenario
from hexaleg.sweep.optimal import OptimalPoint, OptimalSpec
from hexaleg.sweep.ranges import POINT_BYTES, parse_range
from hexaleg.sweep.spec_tables import (
    GAIT_PARAMETERS,
    PAPER_UNIT_PARAMETERS,
    gait_table,
    spring_tables,
    sweep_table,
)

LAYOUTS: tuple[str, ...] = ("product", "each")
"""How spring groups combine: every combination of all groups' values, or one group at a time."""
SECTIONS: tuple[str, ...] = ("sweep", "gait", "springs", "contact", "motor", "optimal")
"""Top-level tables of a sweep spec file."""


def _check_spring_value(name: str, param: str, values: Sequence[float]) -> None:
    lo, hi = min(values), max(values)
    if param in ("k", "k_minus") and lo < 0:
        raise InvalidParameterError(name, lo, "≥ 0 (N·m/rad)")
    if param == "theta_k" and lo <= 0:  # θ⁻ < θ⁺ (eq. 8 with a dead zone of positive width)
        raise InvalidParameterError(name, lo, "> 0 (rad)")
    if param == "dead_zone" and not (lo > 0 and hi < 1):
        raise InvalidParameterError(name, lo if lo <= 0 else hi,
                                    "a fraction of the half range of motion in (0, 1)")


def _check_group(group: str, params: Mapping[str, Any]) -> None:
    """One spring group's parameters: known, non-empty, in range, ``k`` and one dead zone."""
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


def _axes(params: Mapping[str, Any]) -> list[tuple[str, tuple]]:
    return [(k, v) for k, v in params.items() if isinstance(v, tuple)]


def _combinations(params: Mapping[str, Any]) -> list[dict[str, Any]]:
    """Every combination of the axes (tuples) of ``params``, with its fixed values."""
    fixed = {k: v for k, v in params.items() if not isinstance(v, tuple)}
    axes = _axes(params)
    return [{**fixed, **dict(zip([a for a, _ in axes], combo, strict=True))}
            for combo in itertools.product(*(vals for _, vals in axes))]


@named_arguments
@dataclass(frozen=True)
class SweepSpec:
    """A sweep: fixed and varied gait parameters, spring groups and their designs.

    Attributes:
        run: Robot, motor, force objective and contact settings.
        gait: Gait parameters, :data:`GAIT_PARAMETERS` → a value (fixed) or a tuple (an axis).
        springs: Group → (parameter → value or tuple of values), SI,
            :data:`~hexaleg.design.evaluator.SPRING_PARAMETERS`.
        joints: Group → explicit joint names; groups not listed are a joint class or one joint
            (``Robot.joints(group)``).
        layout: ``"product"`` (all combinations of every axis) or ``"each"`` (one sprung group
            per point: the product of that group's axes, the other groups without springs).
        metric: Metric the summary ranks by (:data:`~hexaleg.design.evaluator.METRICS`).
        chunk_size: Points per task and per part file (does not change the results).
        optimal: With it, each point is the optimum of a spring family on a set of the groups
            (:class:`~hexaleg.sweep.optimal.OptimalSpec`) and the groups carry no design
            parameters.
        motion: A log of the robot's own gait swept instead of gaits (``--motion``,
            :mod:`~hexaleg.sweep.logged`), or None. cycle: Which part of it.

    Raises:
        UnknownNameError: an unknown gait or spring parameter, metric or layout (lists the
            valid ones).
        InvalidParameterError: an empty grid, a value out of range, a group without ``k`` or
            without exactly one dead-zone choice; with ``optimal``, no group or a group with
            design parameters.
    """

    run: Scenario = field(default_factory=Scenario.load)
    gait: Mapping[str, float | tuple[float, ...]] = field(default_factory=dict)
    springs: Mapping[str, Mapping[str, float | tuple[float, ...]]] = field(default_factory=dict)
    joints: Mapping[str, tuple[str, ...]] = field(default_factory=dict)
    layout: str = "product"
    metric: str = DEFAULT_METRIC
    chunk_size: int = 50
    optimal: OptimalSpec | None = None
    motion: str | None = None
    cycle: str = "auto"

    def __post_init__(self) -> None:
        for name in self.gait:
            if name not in GAIT_PARAMETERS:
                raise UnknownNameError("gait parameter", name, GAIT_PARAMETERS)
        for group, params in self.springs.items():
            if self.optimal is None:
                _check_group(group, params)
            elif params:
                raise InvalidParameterError(
                    f"springs.{group}", sorted(params), "no design parameters in an optimal "
                    "sweep (only joints = [...]): the program chooses them")
        if self.optimal is not None and not self.springs:
            raise InvalidParameterError("springs", {}, "at least one [springs.<group>] table "
                                        "naming the joints an optimal sweep designs")
        for group in self.joints:
            if group not in self.springs:
                raise UnknownNameError("spring group", group, self.springs)
        if self.layout not in LAYOUTS:
            raise UnknownNameError("layout", self.layout, LAYOUTS)
        if self.metric not in METRICS:
            raise UnknownNameError("metric", self.metric, METRICS)
        integer("chunk_size", self.chunk_size, low=1)
        count("sweep grid (points: gaits × designs)", self.grid_size(), item_bytes=POINT_BYTES,
              item="one point", fix="split the sweep or use fewer values on an axis: "
              + (" × ".join(f"{n} ({len(v)})" for n, v in self.axes()) or "no axes"))
        for g in self.gaits() if self.motion is None else ():  # valid (GaitParams checks)
            self.run.with_gait(g)

    @classmethod
    def from_mapping(cls, data: Mapping[str, Any], where: str = "sweep spec") -> SweepSpec:
        """A spec from parsed TOML (see ``docs/sweep.md``).

        ``[sweep]`` holds ``metric``, ``layout``, ``chunk_size`` and the
        :class:`~hexaleg.scenario.scenario.Scenario` keys ``robot`` (a registered name or a robot
        TOML, relative to the spec's directory), ``motor``, ``objective``; ``[contact]`` the
        :class:`~hexaleg.dynamics.contact.ContactParams`; ``[gait]`` gait parameters;
        ``[springs.<group>]`` one table per group with an optional ``joints`` list;
        ``[optimal]`` (:class:`~hexaleg.sweep.optimal.OptimalSpec`) makes each point a
        family's optimum on a set of groups. A scalar is fixed, a list or a range table
        ``{start, stop, num, scale = "linear" | "log"}`` is an axis. Keys in the
        paper's units (:data:`PAPER_UNIT_PARAMETERS`) are converted to SI through
        :mod:`hexaleg.units`.

        Raises:
            UnknownNameError: unknown table or key (lists the valid ones).
            ConfigError: a section that is not a table, a value of the wrong type.
            InvalidParameterError: an empty grid or a value out of range.
        """
        for name, table in check_tables(data, SECTIONS, where).items():
            if not isinstance(table, Mapping):
                raise ConfigError(f"{where}: {name} = {table!r}; expected a table, [{name}] "
                                  "with its keys on the lines below")
        run, sweep = sweep_table(data, where)
        gait = gait_table(data.get("gait", {}))
        springs, joints = spring_tables(data.get("springs", {}), where)
        optimal = None
        if "optimal" in data:
            optimal = OptimalSpec.from_mapping(data["optimal"], where)
            sweep.setdefault("metric", OBJECTIVE_METRIC[run.objective])  # what is optimised
        return cls(run=run, gait=gait, springs=springs, joints=joints, optimal=optimal, **sweep)

    @classmethod
    def from_toml(cls, path: str | Path) -> SweepSpec:
        """A spec from a TOML file (see :meth:`from_mapping`); a robot ``.toml`` path in
        ``[sweep]`` is relative to the spec's directory."""
        data = load_toml(path)
        sweep = data.get("sweep")
        if isinstance(sweep, dict) and str(sweep.get("robot")).endswith(".toml"):
            sweep["robot"] = str(Path(path).parent / sweep["robot"])
        return cls.from_mapping(data, str(path))

    @classmethod
    def one_group(cls, joints: str, values: Mapping[str, str | None], *,
                  period: str | None = None, samples: int | None = None,
                  optimal: OptimalSpec | None = None, robot: str = "hexaleg") -> SweepSpec:
        """A sweep of one spring group from command-line texts (``hexaleg sweep --joints …``).

        Args:
            joints: Joint class or joint.
            values: Spring parameter → its text (``VALUE``, ``V1,V2,…`` or
                ``START:STOP:NUM[:log]``, :func:`~hexaleg.sweep.ranges.parse_range`), or
                None where not given; ``k`` is required without ``optimal``, nothing with it.
            period: The gait period's text, or None.
            samples: Samples per gait cycle, or None.
            optimal: The family's optimum on the group at each gait instead of a grid of designs
                (ranked by the objective's metric).
            robot: A registered robot or a robot TOML file.

        Raises:
            InvalidParameterError: no joints, no ``k`` without ``optimal``, a design value with
                it; a bad value (named by its flag).
        """
        given = {name: v for name, v in values.items() if v is not None}
        if not joints or (optimal is None and "k" not in given):
            raise InvalidParameterError("--joints/--k", (joints, values.get("k")),
                                        "a spec file, or --joints with --k or --family")
        if optimal is not None and given:
            raise InvalidParameterError(
                "/".join(f"--{n.replace('_', '-')}" for n in given), "given with --family",
                "either a grid of designs (--k …) or the family's optimum (--family)")
        params = {name: parse_range(f"--{name.replace('_', '-')}", v)
                  for name, v in given.items()}
        gait: dict[str, Any] = {}
        if period is not None:
            gait["period"] = parse_range("--period", period)
        if samples is not None:
            gait["samples"] = samples
        run = Scenario.load(robot)
        if optimal is None:
            return cls(run=run, springs={joints: params}, gait=gait)
        return cls(run=run, springs={joints: {}}, gait=gait, optimal=optimal,
                   metric=OBJECTIVE_METRIC[run.objective])

    # -- the grid

    def gaits(self) -> list[dict[str, Any]]:
        """Every gait of the grid as :class:`~hexaleg.motion.params.GaitParams` keywords (a
        logged sweep: the log, ``{"motion": path, "cycle": cycle}``)."""
        if self.motion is not None:
            return [{"motion": self.motion, "cycle": self.cycle}]
        return _combinations(self.gait)

    def designs(self) -> list[dict[str, dict[str, float]]]:
        """Every spring design of the grid, in point order within one gait."""
        if not self.springs:
            return [{}]
        per_group = {g: _combinations(self.springs[g]) for g in self.springs}
        if self.layout == "each":
            return [{g: d} for g in self.springs for d in per_group[g]]
        return [dict(zip(per_group, combo, strict=True))
                for combo in itertools.product(*per_group.values())]

    def points_of_gait(self) -> list[Any]:
        """The designs of one gait, in point order: :meth:`designs`, or for an optimal sweep
        (family, sprung groups) pairs (:meth:`OptimalSpec.points`)."""
        if self.optimal is not None:
            points: list[OptimalPoint] = self.optimal.points(list(self.springs))
            return points
        return self.designs()

    @property
    def n_points(self) -> int:
        """Number of points: gaits × designs (:meth:`grid_size`)."""
        return self.grid_size()

    def axes(self) -> list[tuple[str, tuple]]:
        """The grid's axes, ``(name, values)``: gait parameters, then ``<group>.<parameter>``."""
        return [*((f"gait.{k}", v) for k, v in _axes(self.gait)),
                *((f"{g}.{k}", v) for g, p in self.springs.items() for k, v in _axes(p))]

    def grid_size(self) -> int:
        """Number of points, computed from the axes' lengths without listing the grid (so a
        grid too large to list is refused by name, not by a ``MemoryError``)."""
        gaits = math.prod(len(v) for _, v in _axes(self.gait))
        if self.optimal is not None:
            groups = len(self.springs)
            sets = {"each": groups, "all": 1, "every": 2**groups - 1}[self.optimal.sets]
            return gaits * len(self.optimal.family) * sets
        per_group = [math.prod(len(v) for _, v in _axes(p)) for p in self.springs.values()]
        designs = sum(per_group) if self.layout == "each" else math.prod(per_group)
        return gaits * max(designs, 1)  # no groups: one design, the baseline

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
            "run": {"robot": self.run.robot, "motor": self.run.table("motor").get("base"),
                    "objective": self.run.objective,
                    "contact": dataclasses.asdict(self.run.contact)},
            "gait": {k: plain(v) for k, v in self.gait.items()},
            "springs": {g: {k: plain(v) for k, v in p.items()} for g, p in self.springs.items()},
            "joints": {g: list(j) for g, j in self.joints.items()},
            "layout": self.layout,
            **({"optimal": self.optimal.to_dict()} if self.optimal is not None else {}),
            **({"motion": {"path": self.motion, "cycle": self.cycle}} if self.motion else {}),
        }
