"""``hexaleg simulate``'s inputs: robot, gait, motor and contact, springs, settings.

A registered robot (or one's own robot TOML) with its own gait, motor and contact settings; a
config file's ``[gait]``, ``[motor]``, ``[contact]`` tables on top (as ``hexaleg report`` reads
them, :class:`hexaleg.report.config.ReportConfig`) and its ``[simulate]`` table
(:class:`~hexaleg.simulation.run.Settings`); the springs of a design file
(:func:`hexaleg.design.chain.design_file.load_design`, on the gait the design was made for unless
the config gives a ``[gait]``) or, without one, the springs ``hexaleg report`` leads with on the
same run (:func:`hexaleg.report.answer.answer_section`: ``hexaleg-design/design.json`` when it
was made for this robot and gait, else the quick answer — the linear family's global optimum
through ``hexaleg design``'s first stage), so that plain ``hexaleg simulate`` checks the
report's answer. Where the report has no answer (a payload, a logged motion, a motor outside the
catalogue) the globally optimal linear springs on the robot's spring class
(:func:`hexaleg.design.search.optimal.optimal_springs`), with a note saying why.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from hexaleg.design.chain.design_file import load_design
from hexaleg.design.search.optimal import optimal_springs
from hexaleg.dynamics.prepare import Prepared, prepare
from hexaleg.motion.legged import tripod_gait
from hexaleg.report.answer import answer_springs
from hexaleg.report.config import ReportConfig
from hexaleg.robot.springs import SpringSet
from hexaleg.scenario.run_warnings import gait_defaults, run_warnings
from hexaleg.scenario.scenario import Scenario
from hexaleg.simulation.result import Simulation
from hexaleg.simulation.run import simulate
from hexaleg.simulation.settings import Settings

DEFAULT_FAMILY = "linear"
"""The spring family of the default design (its optimum has no geometry to search: global)."""


@dataclass(frozen=True, eq=False)
class Study:
    """Everything one ``hexaleg simulate`` runs on.

    Attributes:
        robot_name: The registered name or TOML file.
        prepared: The gait prepared with the motor and contact settings.
        springs: The springs simulated.
        design: Where the springs came from, in words.
        settings: How to simulate.
        objective: The analysis' force objective.
        notes: Caveats (the config's, a constant-torque optimum, …).
        warnings: The run's warnings (:func:`hexaleg.scenario.run_warnings.run_warnings`).
        gait_defaults: What its sized gait defaults chose
            (:func:`hexaleg.scenario.run_warnings.gait_defaults`), or None.
    """

    robot_name: str
    prepared: Prepared
    springs: SpringSet
    design: str
    settings: Settings
    objective: str
    notes: tuple[str, ...]
    warnings: tuple[str, ...] = ()
    gait_defaults: dict[str, Any] | None = None

    def run(self) -> Simulation:
        """Simulate (:func:`hexaleg.simulation.run.simulate`)."""
        p = self.prepared
        return simulate(p.robot, p.motion, p.motor, self.springs, self.settings,
                        contact=p.contact, objective=self.objective, prepared=p)


def load_study(scenario: Scenario, springs: str | Path | None = None,
               overrides: Mapping[str, Any] | None = None) -> Study:
    """The study of ``hexaleg simulate`` (module docstring) for a run.

    Args:
        scenario: The run (:func:`hexaleg.commands.options.load_run`): robot, gait or log,
            actuator, contact; its ``[simulate]`` table the settings.
        springs: A design file (``design.json``), or None for the optimal linear springs.
        overrides: :class:`Settings` fields given on the command line (over ``[simulate]``).

    Raises:
        ConfigError: a file that cannot be read or has the wrong types (named).
        UnknownNameError: an unknown table, key, family or joint (lists the valid ones).
        InvalidParameterError: a value out of range (named).
        InfeasibleForcesError: the gait has no admissible contact forces.
        TorqueLimitError: the gait needs more than the motor's stall torque.
    """
    s = scenario
    where = s.where
    report = ReportConfig.from_scenario(s)
    settings = Settings.from_mapping(s.table("simulate"), f"{where} [simulate]")
    if overrides:
        settings = dataclasses.replace(settings, **{k: v for k, v in overrides.items()
                                                    if v is not None})
    gait, notes = report.gait, list(report.notes)
    designed = load_design(springs, s.robot) if springs is not None else None
    if s.recorded is not None:
        if designed is not None and designed.gait is not None:
            notes.append(f"the design file's springs were designed on its own gait "
                         f"({designed.gait.samples} samples per cycle); the logged motion "
                         "replaces it here, so the prediction differs from the design's")
    elif designed is not None and designed.log is not None:
        notes.append(f"the design file's springs were designed on the motion log {designed.log}; "
                     "without --motion this run plays the robot's generated gait, so the "
                     f"prediction differs from the design's (give --motion {designed.log})")
    elif designed is not None and designed.gait is not None:
        if "gait" in s.tables:
            notes.append(f"the design file's springs were designed at {designed.gait.samples} "
                         f"samples per cycle on its own gait; {where} [gait] replaces it here "
                         f"({gait.samples} samples), so the prediction differs from the design's")
        else:
            gait = designed.gait
            notes.append(f"the gait of the design file ({gait.samples} samples per cycle), so "
                         "the prediction is the design's own")
    played = s.recorded if s.recorded is not None else tripod_gait(s.model, gait)
    prepared = prepare(s.model, played, motor=report.motor, contact=report.contact)
    objective = report.report.objective
    if "springs" in s.tables:
        notes.append(f"{where} [springs] is the report's design and is not simulated; give the "
                     "springs to simulate with --springs design.json")
    spring_set: SpringSet | None
    if designed is not None:
        spring_set = designed.springs
        design = f"the design file {springs}"
    else:
        spring_set, design, why = answer_springs(report, prepared)
        notes += why
        if spring_set is None:
            notes.append("hexaleg report has no answer on this run (the notes above say why): "
                         "the optimal linear springs are simulated instead")
    if spring_set is None:
        kind = s.description.spring_class_of(s.model)
        best = optimal_springs(prepared, [kind], DEFAULT_FAMILY, objective)
        spring_set = best.springs
        design = (f"the globally optimal {DEFAULT_FAMILY} springs on the {kind} joints "
                  f"(optimal_springs, {objective} objective)")
        notes += list(best.notes)
    warned = run_warnings(prepared.robot, played, report.motor, desc=s.description,
                          gait=gait if s.recorded is None else None)
    return Study(s.robot, prepared, spring_set, design, settings, objective, tuple(notes),
                 warned, gait_defaults(s.description, gait if s.recorded is None else None))


__all__ = ["DEFAULT_FAMILY", "Study", "load_study"]
