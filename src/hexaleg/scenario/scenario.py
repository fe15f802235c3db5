"""The one description of a run: :class:`Scenario`.

A run is a robot (a registered name or a robot description TOML), its actuators, the contact,
and either its gait — the robot's own gait parameters with a config file's ``[gait]`` keys on
top — or a recorded log of its own gait with the part of it that is one cycle. Every command
builds its run here, from the same three inputs (the robot, a config file, ``--motion`` and
``--cycle``), with the same checks, so the same bad value is the same named error everywhere
and every command says the same warnings and notes of the run.

A scenario is the only run object below the commands (pvlib's ``ModelChain`` takes a built
system and never re-parses it): frozen and picklable — a worker process receives it whole and
loads the robot from its own per-process cache (:func:`robot_model`), so the URDF is built once
per process — with the run's motion (:meth:`Scenario.motion`), its preparation
(:meth:`Scenario.prepare`), the same run under changed conditions (:meth:`Scenario.under`), at
another sampling (:meth:`Scenario.with_samples`) and its JSON form (:meth:`Scenario.data`).

The config file's tables are read once (:data:`TABLES` lists every table any command reads and
which one); :meth:`Scenario.load` checks the run's own (``[gait]``, ``[contact]``, ``[motor]``)
and refuses a ``[gait]`` table with a log; the tables of the stages above it (``[design]``,
``[codesign]``, ``[simulate]``, ``[report]``, ``[springs]``, ``[payload]``, ``[view]``) ride on
:attr:`Scenario.tables` and are checked by their owners, all of them by every command
(:func:`hexaleg.commands.options.load_run`).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from hexaleg.checks import one_of
from hexaleg.config import check_tables, from_mapping, load_toml
from hexaleg.dynamics.contact import ContactParams, check_objective
from hexaleg.dynamics.prepare import Prepared, prepare
from hexaleg.errors import InvalidParameterError
from hexaleg.motion.legged import tripod_gait
from hexaleg.motion.params import GaitParams, gait_parameters
from hexaleg.motion.scaling import robot_gait
from hexaleg.motion.trajectory import Motion
from hexaleg.quantities import quantity
from hexaleg.robot.actuator import Actuator
from hexaleg.robot.catalogue import motor_from_mapping
from hexaleg.robot.description import RobotDescription
from hexaleg.robot.model import Robot
from hexaleg.robot.payload import with_payload
from hexaleg.robot.registry import description
from hexaleg.scenario.condition import Condition, condition_gait
from hexaleg.scenario.logged import logged_motion, quality_note, refuse_gait_table
from hexaleg.scenario.run_warnings import run_warnings

TABLES: dict[str, str] = {
    "gait": "every command but codesign (which searches the gait): keys over the robot's own "
            "gait (docs/gaits.md)",
    "contact": "every command: friction and contact settings (codesign reads mu and "
               "torque_limits, its floor, and refuses the others by name)",
    "motor": "report, simulate, view, design, codesign, sweep: one servo on every joint instead "
             "of the robot's own",
    "payload": "report: a payload on the base",
    "springs": "report: the springs the report analyses",
    "report": "report: what the report shows",
    "view": "view: how a motion is drawn",
    "design": "design, and codesign's spring rules: the spring design",
    "mission": "design: how the robot is used between folds into the sphere (metres_per_fold)",
    "simulate": "simulate: the forward simulation's settings",
    "codesign": "codesign: the gait and spring co-design",
}
"""Every table a config file may have, and which command reads it. A file may carry tables
other commands read; each command checks every table, so a bad value is an error in all."""


_ROBOTS: dict[tuple[str, float], Robot] = {}
"""This process's robots: (robot, payload in kg) → the loaded model (:func:`robot_model`)."""


def robot_model(robot: str, payload: float = 0.0) -> Robot:
    """The robot ``robot`` (a registered name or a description TOML), loaded once per process,
    with a point-mass payload of ``payload`` kg on its base (:func:`hexaleg.robot.payload.
    with_payload`; 0: none).

    Raises:
        UnknownNameError: an unknown robot. ConfigError: a TOML that cannot be read.
    """
    key = (robot, float(payload))
    if key not in _ROBOTS:
        if payload:
            bare = robot_model(robot)
            _ROBOTS[key] = with_payload(bare, payload, note=f"payload {100 * payload / bare.mass:g}"
                                        " % of the robot's mass")
        else:
            _ROBOTS[key] = description(robot).load()
    return _ROBOTS[key]


def clear_robots() -> None:
    """Forget the robots this process loaded (e.g. after editing a URDF)."""
    _ROBOTS.clear()


@dataclass(frozen=True, eq=False)
class Scenario:
    """One run (module docstring).

    Attributes:
        robot: The robot's registered name or description file.
        gait: The gait: the robot's own parameters with the file's ``[gait]`` keys on top (with
            a log, the robot's own: it does not apply).
        contact: Contact settings (``[contact]``).
        actuator: The servos: the file's ``[motor]`` on every joint, else the robot's own
            (:meth:`~hexaleg.robot.description.RobotDescription.actuator`).
        objective: The force-distribution objective (:data:`hexaleg.dynamics.contact.
            OBJECTIVES`; default ``"joule"``, the motor-energy optimum).
        payload: A point mass on the base, kg (0: none; :meth:`under` a payload condition).
        tables: The config file's tables as read (every one in :data:`TABLES`).
        where: Where the tables came from (the file's name), for messages.
        log: A recorded log of the robot's own gait (``--motion``), or None.
        cycle: Which part of the log is one cycle (``"auto"``, ``"whole"``, ``"T0:T1"``).
        recorded: The log's cycle (:func:`hexaleg.scenario.logged.logged_motion`), or None.
        notes: What the user should know about the run: the robot's loading notes and, with a
            log, where the motion came from and how good it is.
    """

    robot: str
    gait: GaitParams
    contact: ContactParams
    actuator: Actuator
    objective: str = "joule"
    payload: float = 0.0
    tables: Mapping[str, Any] = field(default_factory=dict)
    where: str = "config"
    log: str | None = None
    cycle: str = "auto"
    recorded: Motion | None = None
    notes: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        check_objective(self.objective)

    @classmethod
    def load(cls, robot: str = "hexaleg", config: str | Path | None = None, *,
             log: str | Path | None = None, cycle: str = "auto") -> Scenario:
        """The run of ``--robot ROBOT --config FILE --motion LOG --cycle CYCLE``.

        Raises:
            ConfigError: the file cannot be read, or a value has the wrong type.
            UnknownNameError: an unknown robot, table or key (lists the valid ones).
            InvalidParameterError: a value out of range; a ``[gait]`` table with a log; the
                log's named bad input.
        """
        tables = load_toml(config) if config else {}
        return cls.from_tables(robot, tables, str(config) if config else "config", log=log,
                               cycle=cycle)

    @classmethod
    def from_tables(cls, robot: str, tables: Mapping[str, Any], where: str = "config", *,
                    log: str | Path | None = None, cycle: str = "auto") -> Scenario:
        """The run from a parsed config document (:meth:`load`)."""
        check_tables(tables, tuple(TABLES), where)
        desc = description(robot)
        if log is not None:
            refuse_gait_table(tables, where, log)
        table = tables.get("gait", {})
        gait = robot_gait(desc, table=table, where=f"{where} [gait]").updated(
            table, f"{where} [gait]")
        contact = from_mapping(ContactParams, tables.get("contact", {}), f"{where} [contact]")
        motor = tables.get("motor")
        given = motor_from_mapping(motor, f"{where} [motor]") if motor is not None else None
        model = robot_model(robot)  # after the run's own tables are checked: it is the slow part
        actuator = given if given is not None else desc.actuator(model)
        motion = logged_motion(model, log, cycle) if log is not None else None
        notes = (*model.notes, *((quality_note(motion),) if motion is not None else ()))
        return cls(robot=robot, gait=gait, contact=contact, actuator=actuator, tables=tables,
                   where=where, log=None if log is None else str(log), cycle=cycle,
                   recorded=motion, notes=notes)

    @property
    def description(self) -> RobotDescription:
        """The robot's description (:func:`hexaleg.robot.registry.description`)."""
        return description(self.robot)

    @property
    def model(self) -> Robot:
        """The robot with the run's payload, loaded once per process (:func:`robot_model`)."""
        return robot_model(self.robot, self.payload)

    def table(self, name: str) -> Mapping[str, Any]:
        """The file's table ``name`` (:data:`TABLES`), empty when it has none."""
        return self.tables.get(name, {})

    def motion(self) -> Motion:
        """The motion of the run: the log's cycle, else one cycle of the gait."""
        return self.recorded if self.recorded is not None else tripod_gait(self.model, self.gait)

    def prepare(self, motion: Motion | None = None) -> Prepared:
        """The run prepared once (:func:`hexaleg.dynamics.prepare.prepare`): everything that
        does not depend on the springs.

        Args:
            motion: The run's motion when it is already made (:meth:`motion` of a run with the
                same robot, payload and gait, or log: the friction and the actuator do not
                change it); default made here. Making a gait (its balance sway) is most of a
                preparation: 99 % of the robustness maps' on Solo-12, profiled.
        """
        return prepare(self.model, self.motion() if motion is None else motion,
                       motor=self.actuator, contact=self.contact)

    def replace(self, **changes: Any) -> Scenario:
        """The same run with fields replaced (:func:`dataclasses.replace`), e.g. another
        ``gait``, ``contact`` or ``objective``."""
        return dataclasses.replace(self, **changes)

    def with_gait(self, overrides: Mapping[str, Any]) -> Scenario:
        """The same run with gait fields replaced (``overrides``: field → value, e.g. a sweep's
        grid point).

        Raises:
            UnknownNameError: a key that is not a :class:`GaitParams` field (lists them).
            InvalidParameterError: a value out of range.
        """
        fields = [f.name for f in dataclasses.fields(GaitParams) if f.init]
        for key in overrides:
            one_of("gait parameter", key, fields)
        return self.replace(gait=dataclasses.replace(self.gait, **overrides))

    def with_samples(self, samples: int) -> Scenario:
        """The same run sampled ``samples`` times a cycle (a log keeps its own samples).

        Raises:
            InvalidParameterError: fewer samples than a gait needs
                (:data:`hexaleg.motion.limits.MIN_SAMPLES`).
        """
        if self.recorded is not None:
            return self
        return self.replace(gait=dataclasses.replace(self.gait, samples=samples))

    def under(self, condition: Condition) -> Scenario:
        """The same run under ``condition`` (:mod:`hexaleg.scenario.condition`): its gait scaled
        (:func:`~hexaleg.scenario.condition.condition_gait`), its μ, its payload (a fraction of
        the robot's mass, on top of the run's).

        Raises:
            InvalidParameterError: a run of a recorded log (its motion cannot be varied), or a
                slope the condition carries out of range.
        """
        if self.recorded is not None:
            raise InvalidParameterError("condition", condition.label(),
                                        f"a gait: the run replays the log {self.log}, whose "
                                        "motion cannot be varied")
        contact = (self.contact if condition.mu is None
                   else dataclasses.replace(self.contact, mu=condition.mu))
        payload = self.payload + condition.payload * robot_model(self.robot).mass
        return self.replace(gait=condition_gait(self.gait, condition), contact=contact,
                            payload=payload)

    def key(self) -> tuple[Any, ...]:
        """What makes two runs the same analysis (a cache key): the robot, payload, actuator,
        objective, contact and gait, or the log and its cycle."""
        motion = (self.log, self.cycle) if self.recorded is not None else self.gait
        return (self.robot, self.payload, self.actuator, self.objective, self.contact, motion)

    def data(self) -> dict[str, Any]:
        """The run in JSON form, every number ``{value, unit}`` in SI: robot, gait
        (:func:`~hexaleg.motion.params.gait_parameters`), contact, actuator, objective, payload,
        log and cycle."""
        c = self.contact
        return {"robot": self.robot, "gait": gait_parameters(self.gait),
                "contact": {"mu": quantity(c.mu, "1"), "cone": c.cone,
                            "min_normal_force": quantity(c.min_normal_force, "N"),
                            "torque_limits": c.torque_limits,
                            "regularization": quantity(c.regularization, "W/(N·m)²")},
                "actuator": self.actuator.name, "objective": self.objective,
                "payload": quantity(self.payload, "kg"), "log": self.log, "cycle": self.cycle}

    def warnings(self, motion: Motion | None = None,
                 actuator: Actuator | None = None) -> tuple[str, ...]:
        """The run's warnings (:func:`hexaleg.scenario.run_warnings.run_warnings`), the same
        lines in every command: for ``motion`` (default :meth:`motion`) and ``actuator``
        (default :attr:`actuator`)."""
        return run_warnings(self.model, motion if motion is not None else self.motion(),
                            actuator if actuator is not None else self.actuator,
                            desc=self.description, gait=self.gait if self.log is None else None)


__all__ = ["TABLES", "Scenario", "clear_robots", "robot_model"]
