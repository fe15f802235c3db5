"""The one description of a run: :class:`Scenario`.

A run is a robot (a registered name or a robot description TOML), its actuators, the contact,
and either its gait — the robot's own gait parameters with a config file's ``[gait]`` keys on
top — or a recorded log of its own gait with the part of it that is one cycle. Every command
builds its run here, from the same three inputs (the robot, a config file, ``--motion`` and
``--cycle``), with the same checks, so the same bad value is the same named error everywhere
and every command says the same warnings and notes of the run.

The config file's tables are read once (:data:`TABLES` lists every table any command reads and
which one); :meth:`Scenario.load` checks the run's own (``[gait]``, ``[contact]``, ``[motor]``)
and refuses a ``[gait]`` table with a log; the tables of the stages above it (``[design]``,
``[codesign]``, ``[simulate]``, ``[report]``, ``[springs]``, ``[payload]``, ``[view]``) ride on
:attr:`Scenario.tables` and are checked by their owners, all of them by every command
(:func:`hexaleg.commands.options.load_run`).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from hexaleg.config import check_tables, from_mapping, load_toml
from hexaleg.dynamics.contact import ContactParams
from hexaleg.dynamics.prepare import Prepared, prepare
from hexaleg.motion.legged import tripod_gait
from hexaleg.motion.params import GaitParams
from hexaleg.motion.scaling import robot_gait
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.actuator import Actuator
from hexaleg.robot.catalogue import motor_from_mapping
from hexaleg.robot.description import RobotDescription
from hexaleg.robot.model import Robot
from hexaleg.robot.registry import description
from hexaleg.scenario.logged import logged_motion, quality_note, refuse_gait_table
from hexaleg.scenario.run_warnings import run_warnings

TABLES: dict[str, str] = {
    "gait": "every command but codesign (which searches the gait): keys over the robot's own "
            "gait (docs/gaits.md)",
    "contact": "every command but codesign ([codesign.constraints] mu): friction and contact "
               "settings",
    "motor": "report, simulate, view, design: one servo on every joint instead of the robot's "
             "own",
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


@dataclass(frozen=True, eq=False)
class Scenario:
    """One run (module docstring).

    Attributes:
        robot: The robot's registered name or description file.
        description: Its description (:mod:`hexaleg.robot.registry`).
        model: The robot, loaded once.
        gait: The gait: the robot's own parameters with the file's ``[gait]`` keys on top (with
            a log, the robot's own: it does not apply).
        contact: Contact settings (``[contact]``).
        actuator: The servos: the file's ``[motor]`` on every joint, else the robot's own
            (:meth:`~hexaleg.robot.description.RobotDescription.actuator`).
        tables: The config file's tables as read (every one in :data:`TABLES`).
        where: Where the tables came from (the file's name), for messages.
        log: A recorded log of the robot's own gait (``--motion``), or None.
        cycle: Which part of the log is one cycle (``"auto"``, ``"whole"``, ``"T0:T1"``).
        motion: The log's cycle (:func:`hexaleg.scenario.logged.logged_motion`), or None.
        notes: What the user should know about the run: the robot's loading notes and, with a
            log, where the motion came from and how good it is.
    """

    robot: str
    description: RobotDescription
    model: Robot
    gait: GaitParams
    contact: ContactParams
    actuator: Actuator
    tables: Mapping[str, Any] = field(default_factory=dict)
    where: str = "config"
    log: str | None = None
    cycle: str = "auto"
    motion: Motion | None = None
    notes: tuple[str, ...] = ()

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
        gait = robot_gait(desc).updated(tables.get("gait", {}), f"{where} [gait]")
        contact = from_mapping(ContactParams, tables.get("contact", {}), f"{where} [contact]")
        model = desc.load()
        motor = tables.get("motor")
        actuator = (motor_from_mapping(motor, f"{where} [motor]") if motor is not None
                    else desc.actuator(model))
        motion = logged_motion(model, log, cycle) if log is not None else None
        notes = (*model.notes, *((quality_note(motion),) if motion is not None else ()))
        return cls(robot=robot, description=desc, model=model, gait=gait, contact=contact,
                   actuator=actuator, tables=tables, where=where,
                   log=None if log is None else str(log), cycle=cycle, motion=motion,
                   notes=notes)

    def table(self, name: str) -> Mapping[str, Any]:
        """The file's table ``name`` (:data:`TABLES`), empty when it has none."""
        return self.tables.get(name, {})

    def played(self) -> Motion:
        """The motion of the run: the log's cycle, else one cycle of the gait."""
        return self.motion if self.motion is not None else tripod_gait(self.model, self.gait)

    def prepare(self) -> Prepared:
        """The run prepared once (:func:`hexaleg.dynamics.prepare.prepare`): everything that
        does not depend on the springs."""
        return prepare(self.model, self.played(), motor=self.actuator, contact=self.contact)

    def warnings(self, motion: Motion | None = None,
                 actuator: Actuator | None = None) -> tuple[str, ...]:
        """The run's warnings (:func:`hexaleg.scenario.run_warnings.run_warnings`), the same
        lines in every command: for ``motion`` (default :meth:`played`) and ``actuator``
        (default :attr:`actuator`)."""
        return run_warnings(self.model, motion if motion is not None else self.played(),
                            actuator if actuator is not None else self.actuator,
                            desc=self.description, gait=self.gait if self.log is None else None)


__all__ = ["TABLES", "Scenario"]
