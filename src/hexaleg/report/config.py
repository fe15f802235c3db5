"""The report's configuration: ``[report]``, ``[springs]`` and the whole TOML document.

:class:`ReportConfig` (from TOML through :func:`hexaleg.config.from_mapping`) has the optional
tables ``[gait]``, ``[motor]``, ``[contact]``, ``[springs]``, ``[report]`` and ``[payload]``
(:class:`hexaleg.robot.payload.Payload`, carried on the base); ``[view]`` is left
to ``hexaleg view``, which reads the same file. A ``[springs]`` table names a design
(:class:`SpringDesign`: the paper's dead-zone springs of eq. 7–8, 14 placed by
:mod:`hexaleg.design.rules` — centred dead zone, θ_k/A of Section 4.2, k_M of eq. 19) or lists
per-joint springs in SI.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, cast

from hexaleg.checks import count, is_integer, is_real
from hexaleg.config import check_tables, from_mapping, load_toml
from hexaleg.design import rules as design
from hexaleg.design.studies.curves import CURVE_METRICS
from hexaleg.dynamics.contact import OBJECTIVES, ContactParams
from hexaleg.errors import ConfigError, InvalidParameterError, UnknownNameError
from hexaleg.motion.limits import SAMPLE_BYTES
from hexaleg.motion.params import GaitParams
from hexaleg.motion.scaling import robot_gait
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.actuator import Actuator
from hexaleg.robot.catalogue import DEFAULT_MOTOR, motor_from_mapping
from hexaleg.robot.catalogue import motor as motor_by_name
from hexaleg.robot.description import RobotDescription
from hexaleg.robot.model import Robot
from hexaleg.robot.payload import Payload
from hexaleg.robot.springs import SpringSet
from hexaleg.scenario.scenario import TABLES as RUN_TABLES
from hexaleg.scenario.scenario import Scenario

TABLES: tuple[str, ...] = ("gait", "motor", "contact", "springs", "report", "payload")
"""Tables the report reads; a config file may hold the other commands' too
(:data:`hexaleg.scenario.scenario.TABLES`), each checked by its owner."""
SPRING_DESIGNS: tuple[str, ...] = ("paper", "centred", "baseline")
"""``[springs] design``: the paper's rule (:func:`hexaleg.design.rules.paper_style_springs`), a
centred dead zone with a given stiffness (:func:`hexaleg.design.rules.centred_springs`), or the
baseline (no springs)."""


@dataclass(frozen=True)
class ReportParams:
    """The ``[report]`` table: what the report shows.

    Attributes:
        title: Page title.
        objective: Force-distribution objective (:data:`hexaleg.dynamics.contact.OBJECTIVES`).
        curve_joints: Joint class (or one joint) whose spring stiffness the curve varies.
        curve_metrics: Total metrics on the curve (:data:`CURVE_METRICS`), one line each.
        stiffness_min: Smallest stiffness of the curve, N·m/rad, ≥ 0.
        stiffness_max: Largest stiffness, N·m/rad, > ``stiffness_min``; None: 10 × k_M (eq. 19)
            of the curve's joints.
        stiffness_points: Points of the curve, 2 … 1001.
        paper_samples: Samples per period of the paper's single-joint model, ≥ 8 and at most
            :data:`hexaleg.motion.limits.MAX_SAMPLES`
            (:func:`hexaleg.paper.reproduce.reproduce`).
        design: A ``design.json`` of ``hexaleg design`` to lead the page with (its recommended
            springs, :mod:`hexaleg.report.design_section`), or None.
    """

    title: str = "hexaleg gait energy report"
    objective: str = "joule"
    curve_joints: str = "femur"
    curve_metrics: tuple[str, ...] = ("positive_work", "joule", "electrical")
    stiffness_min: float = 0.0
    stiffness_max: float | None = None
    stiffness_points: int = 41
    paper_samples: int = 1024
    design: str | None = None

    def __post_init__(self) -> None:
        if not (isinstance(self.title, str) and self.title.strip()):
            raise InvalidParameterError("report.title", self.title, "a non-empty string")
        if not isinstance(self.curve_joints, str):
            raise InvalidParameterError("report.curve_joints", self.curve_joints,
                                        "a joint class or joint name")
        for name in ("stiffness_points", "paper_samples"):
            if not is_integer(getattr(self, name)):
                raise InvalidParameterError(f"report.{name}", getattr(self, name), "an integer")
        if not isinstance(self.curve_metrics, (tuple, list)):
            raise InvalidParameterError("report.curve_metrics", self.curve_metrics,
                                        "a list of metric names")
        if self.objective not in OBJECTIVES:
            raise InvalidParameterError("report.objective", self.objective,
                                        "one of " + ", ".join(OBJECTIVES))
        metrics = tuple(self.curve_metrics)
        if not metrics or len(set(metrics)) != len(metrics):
            raise InvalidParameterError("report.curve_metrics", self.curve_metrics,
                                        "a non-empty list of distinct metrics")
        for m in metrics:
            if m not in CURVE_METRICS:
                raise UnknownNameError("report.curve_metrics entry", m, CURVE_METRICS)
        object.__setattr__(self, "curve_metrics", metrics)
        if not (is_real(self.stiffness_min) and self.stiffness_min >= 0):
            raise InvalidParameterError("report.stiffness_min", self.stiffness_min,
                                        "a finite number ≥ 0 (N·m/rad)")
        if self.stiffness_max is not None and not (is_real(self.stiffness_max)
                                                   and self.stiffness_max > self.stiffness_min):
            raise InvalidParameterError("report.stiffness_max", self.stiffness_max,
                                        f"None or a finite number > stiffness_min = "
                                        f"{self.stiffness_min} (N·m/rad)")
        if not 2 <= self.stiffness_points <= 1001:
            raise InvalidParameterError("report.stiffness_points", self.stiffness_points,
                                        "an integer in [2, 1001]")
        count("report.paper_samples", self.paper_samples, item_bytes=SAMPLE_BYTES,
              item="one sample", low=8, fix="use fewer samples per period")


@dataclass(frozen=True)
class SpringDesign:
    """The ``[springs]`` table when it names a design instead of listing per-joint springs.

    Attributes:
        design: ``"paper"`` (centred dead zone θ_k/A = 0.426, α = 1.05, k_M of eq. 19 per joint:
            :func:`hexaleg.design.rules.paper_style_springs`), ``"centred"`` (centred dead zone with
            the given ``stiffness`` and ``dead_zone``, α = 1, eq. 7 convention:
            :func:`hexaleg.design.rules.centred_springs`) or ``"baseline"`` (no springs).
        joints: Joint class (``"femur"``) or one joint that gets springs.
        stiffness: ``"centred"`` only (required): k, N·m/rad.
        dead_zone: ``"centred"`` only: θ_k as a fraction of the half range of motion, (0, 1);
            None: the paper's 0.426.
    """

    design: str = "paper"
    joints: str = "femur"
    stiffness: float | None = None
    dead_zone: float | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.joints, str):
            raise InvalidParameterError("springs.joints", self.joints,
                                        "a joint class or joint name")
        if self.design not in SPRING_DESIGNS:
            raise InvalidParameterError("springs.design", self.design,
                                        "one of " + ", ".join(SPRING_DESIGNS))
        if self.design == "centred":
            if not (is_real(self.stiffness) and self.stiffness >= 0):
                raise InvalidParameterError("springs.stiffness", self.stiffness,
                                            "a finite number ≥ 0 (N·m/rad) for design = centred")
            if self.dead_zone is not None and not (is_real(self.dead_zone)
                                                   and 0 < self.dead_zone < 1):
                raise InvalidParameterError("springs.dead_zone", self.dead_zone,
                                            "a fraction of the half range of motion in (0, 1)")
        else:
            for name in ("stiffness", "dead_zone"):
                if getattr(self, name) is not None:
                    raise InvalidParameterError(
                        f"springs.{name}", getattr(self, name),
                        f"not set for design = {self.design} (only design = centred takes it; "
                        "the paper design takes k_M of eq. 19 and θ_k/A = 0.426)")

    def springs(self, robot: Robot, motion: Motion) -> SpringSet:
        """The springs of this design for ``motion``.

        Raises:
            UnknownNameError: ``joints`` is neither a joint class nor a joint (lists both).
        """
        if self.design == "baseline":
            robot.joints(self.joints)  # still reject a misspelt class
            return SpringSet()
        if self.design == "paper":
            return design.paper_style_springs(robot, motion, self.joints)
        dz = design.PAPER_DEAD_ZONE_RATIO if self.dead_zone is None else self.dead_zone
        return design.centred_springs(robot, motion, self.joints, cast(float, self.stiffness),
                                      dead_zone=dz)


def _springs_from_mapping(data: Any, where: str) -> SpringDesign | SpringSet:
    """A ``[springs]`` table: a design (has ``design``) or per-joint tables (SI)."""
    if not isinstance(data, Mapping):
        raise ConfigError(f"{where}: expected a table, got {data!r}")
    if "design" in data:
        return from_mapping(SpringDesign, data, where)
    for key, value in data.items():
        if not isinstance(value, Mapping):  # a design key without design = … , or a typo
            raise UnknownNameError(
                f"key in {where} (give design = ... or per-joint tables [springs.<joint>])",
                key, ("design", "joints", "stiffness", "dead_zone"))
    return SpringSet.from_mapping(data, where)


@dataclass(frozen=True)
class ReportConfig:
    """Everything the report is computed from; the defaults are ``hexaleg report``'s.

    Attributes:
        gait: Gait parameters (``[gait]``).
        motor: The servo of every joint (``[motor]``,
            :func:`hexaleg.robot.catalogue.motor_from_mapping`), or the robot's own motor per joint
            class (a :class:`~hexaleg.robot.motor_set.MotorSet`, from its description).
        contact: Contact settings (``[contact]``).
        springs: The springs the page analyses: a :class:`SpringDesign` (``[springs] design =
            …``) or explicit per-joint springs in SI (``[springs.LF_femur] stiffness = …``,
            :meth:`SpringSet.from_mapping`); None (no ``[springs]`` table): the answer the page
            leads with (:mod:`hexaleg.report.answer`), the paper's design on the robot's spring
            class being the reference (:meth:`reference`).
        report: What the report shows (``[report]``).
        notes: Caveats printed on the report page (set by :meth:`for_robot`; not a TOML table).
        payload: A payload on the base (``[payload]``: ``mass``, ``com``, ``inertia``;
            :class:`hexaleg.robot.payload.Payload`), or None.
        motion: A logged motion (``--motion``, :func:`hexaleg.load_motion`) the report analyses
            instead of the gait ``gait`` would make, or None.
        robot_description: The robot's description (set by :meth:`for_robot`), for the run's
            warnings (:mod:`hexaleg.scenario.run_warnings`: what its gait's sized defaults
            chose), or None.
        robot: The robot as the run names it — a registered name or a description file (set by
            :meth:`from_scenario`), for the quick answer's design run; None: the robot's name.
    """

    gait: GaitParams = field(default_factory=GaitParams)
    motor: Actuator = field(default_factory=lambda: motor_by_name(DEFAULT_MOTOR))
    contact: ContactParams = field(default_factory=ContactParams)
    springs: SpringDesign | SpringSet | None = None
    report: ReportParams = field(default_factory=ReportParams)
    notes: tuple[str, ...] = ()
    payload: Payload | None = None
    motion: Motion | None = None
    robot_description: RobotDescription | None = None
    robot: str | None = None

    @classmethod
    def for_robot(cls, desc: RobotDescription, robot: Robot,
                  data: Mapping[str, Any] | None = None, where: str = "config") -> ReportConfig:
        """The configuration for a robot of the registry (:mod:`hexaleg.robot.registry`).

        The description's gait with the keys the file's ``[gait]`` sets on top; a ``[springs]``
        design and the stiffness curve on the description's spring class unless the file names
        joints; the
        robot's title; the robot's own actuator unless the file has a ``[motor]``
        (:meth:`~hexaleg.robot.description.RobotDescription.actuator`: its catalogue motor, else
        a generic actuator from its URDF limits, whose assumptions become a note on the page);
        the robot's loading notes (feet found, meshes replaced).

        Args:
            desc: The robot description.
            robot: The robot it loads (``desc.load()``).
            data: A parsed config document (as for :meth:`from_mapping`), or None.
            where: Where ``data`` came from, for error messages.
        """
        data = data or {}
        config = cls.from_mapping(data, where)
        given = {t: data.get(t, {}) for t in ("gait", "springs", "report", "contact")}
        gait = robot_gait(desc, table=given["gait"], where=f"{where} [gait]").updated(
            given["gait"], f"{where} [gait]")
        springs = config.springs
        if isinstance(springs, SpringDesign) and "joints" not in given["springs"]:
            springs = dataclasses.replace(springs, joints=desc.spring_class_of(robot))
        report = config.report
        if "curve_joints" not in given["report"]:
            report = dataclasses.replace(report, curve_joints=desc.spring_class_of(robot))
        if "title" not in given["report"]:
            report = dataclasses.replace(report, title=f"{desc.title}: gait energy report")
        from hexaleg.robot.motor_set import motor_classes

        notes = list(robot.notes)
        if "motor" not in data:
            config = dataclasses.replace(config, motor=desc.actuator(robot))
            named = desc.motor if isinstance(desc.motor, Mapping) else {}
            generic = [k for k in motor_classes(robot) if desc.motor is None or
                       (not isinstance(desc.motor, str) and k not in named)]
            if generic:
                notes.append(f"{desc.title} names no catalogue motor for {', '.join(generic)}: "
                             "a generic actuator from its URDF limits there, every other "
                             "constant assumed (each with its value in the page's motor section "
                             "and report.json's motor notes)")
        return dataclasses.replace(config, gait=gait, springs=springs, report=report,
                                   notes=tuple(notes), robot_description=desc)

    @classmethod
    def from_scenario(cls, scenario: Scenario) -> ReportConfig:
        """The configuration of ``hexaleg report`` for a run (:meth:`for_robot` with the run's
        tables; the run's log, when it has one, is the motion analysed, its quality a note).

        Raises:
            ConfigError, UnknownNameError, InvalidParameterError: a bad table (named).
        """
        s = scenario  # its gait, contact and actuator as the run read them, not re-parsed
        config = dataclasses.replace(cls.for_robot(s.description, s.model, s.tables, s.where),
                                     robot=s.robot, gait=s.gait, contact=s.contact,
                                     motor=s.actuator)
        if s.recorded is None:
            return config
        return dataclasses.replace(config, motion=s.recorded,
                                   notes=(*config.notes, *s.notes[len(s.model.notes):]))

    @classmethod
    def from_mapping(cls, data: Mapping[str, Any], where: str = "config") -> ReportConfig:
        """The configuration from a parsed TOML document (all tables optional).

        Args:
            data: Table name → table.
            where: Where it came from (the file name), for error messages.

        Raises:
            UnknownNameError: an unknown table or key (the message lists the valid ones).
            ConfigError: a value of the wrong type.
            InvalidParameterError: a value out of range.
        """
        check_tables(data, tuple(RUN_TABLES), where)
        out: dict[str, Any] = {}
        if "gait" in data:
            out["gait"] = from_mapping(GaitParams, data["gait"], f"{where} [gait]")
        if "motor" in data:
            out["motor"] = motor_from_mapping(data["motor"], f"{where} [motor]")
        if "contact" in data:
            out["contact"] = from_mapping(ContactParams, data["contact"], f"{where} [contact]")
        if "springs" in data:
            out["springs"] = _springs_from_mapping(data["springs"], f"{where} [springs]")
        if "report" in data:
            out["report"] = from_mapping(ReportParams, data["report"], f"{where} [report]")
        if "payload" in data:
            out["payload"] = from_mapping(Payload, data["payload"], f"{where} [payload]")
        return cls(**out)

    @classmethod
    def from_toml(cls, source: str | Path | Mapping[str, Any]) -> ReportConfig:
        """The configuration from a TOML file (or an already parsed document).

        Raises:
            ConfigError: the file cannot be read or parsed, or a value has the wrong type.
            UnknownNameError: an unknown table or key (lists the valid ones).
            InvalidParameterError: a value out of range.
        """
        if isinstance(source, Mapping):
            return cls.from_mapping(source)
        return cls.from_mapping(load_toml(source), str(source))

    def reference(self, robot: Robot) -> SpringDesign | SpringSet:
        """The reference springs: the configured ``[springs]``, else the paper's design carried
        over to the robot (:class:`SpringDesign` ``"paper"`` on its description's spring class,
        the femurs without a description)."""
        if self.springs is not None:
            return self.springs
        desc = self.robot_description
        return SpringDesign(joints="femur" if desc is None else desc.spring_class_of(robot))

    def spring_set(self, robot: Robot, motion: Motion) -> SpringSet:
        """The reference springs (:meth:`reference`) for ``motion`` (a design is evaluated on the
        motion's joint ranges)."""
        springs = self.reference(robot)
        if isinstance(springs, SpringSet):
            return springs
        return springs.springs(robot, motion)
