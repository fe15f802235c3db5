"""hexaleg: whole-robot dynamics and energy analysis of legged robots with nonlinear elastic joints.

The public surface follows the data, one name for one thing (docs/architecture.md):

* the robot: :func:`load` (a registered robot or a description TOML) → :class:`Robot`, its
  servos :class:`Motor`;
* its motion: :class:`GaitParams` → :func:`gait`, a log → :func:`load_motion`, stand → sphere
  :func:`transform_motion`, each a :class:`Motion`;
* the dynamics: :func:`prepare` (once per motion, with :class:`ContactParams`) →
  :class:`Prepared`, whose ``evaluate(springs)`` gives an :class:`Analysis`;
* the springs: a :class:`SpringSet` of the families :class:`LinearSpring`,
  :class:`OneSidedSpring`, :class:`PreloadedSpring`, :class:`DeadZoneSpring`,
  :class:`StiffeningSpring`; the global optimum of their magnitudes :func:`optimal_springs`;
* a whole run and its design: :class:`Scenario` → :class:`DesignChain` (with
  :class:`DesignParams`) → ``design.json``, read back by :func:`load_design`; the gait and its
  springs together :func:`codesign`; sweeps :func:`run_sweep` of a :class:`SweepSpec`;
* the view: :func:`animate`, :func:`export_html`.

Names of earlier releases still work for one release, with a :class:`DeprecationWarning`
saying what replaces them (:data:`_DEPRECATED`).
"""

import importlib
import importlib.metadata
import warnings
from typing import TYPE_CHECKING, Any

from hexaleg.dynamics.contact import ContactParams
from hexaleg.dynamics.prepare import Analysis, Prepared, prepare
from hexaleg.errors import HexalegError
from hexaleg.motion.legged import gait
from hexaleg.motion.params import GaitParams
from hexaleg.motion.trajectory import Motion
from hexaleg.motion.transform import transform_motion
from hexaleg.robot.model import Robot
from hexaleg.robot.motor import Motor
from hexaleg.robot.registry import load
from hexaleg.robot.springs import (
    DeadZoneSpring,
    LinearSpring,
    OneSidedSpring,
    PreloadedSpring,
    SpringSet,
    StiffeningSpring,
)

if TYPE_CHECKING:  # the names __getattr__ imports on first use, for type checkers and the docs
    from hexaleg.design.chain.chain import DesignChain
    from hexaleg.design.chain.config import DesignParams
    from hexaleg.design.chain.design_file import load_design
    from hexaleg.design.codesign.build import codesign
    from hexaleg.design.search.optimal import optimal_springs
    from hexaleg.motion.recorded.load import load_motion
    from hexaleg.outputs.viewer.show import animate, export_html
    from hexaleg.scenario.scenario import Scenario
    from hexaleg.sweep.runner import run_sweep
    from hexaleg.sweep.spec import SweepSpec

__version__ = importlib.metadata.version("hexaleg")
"""The installed distribution's version (one source: ``pyproject.toml``)."""

__all__ = [
    "Analysis",
    "ContactParams",
    "DeadZoneSpring",
    "DesignChain",
    "DesignParams",
    "GaitParams",
    "HexalegError",
    "LinearSpring",
    "Motion",
    "Motor",
    "OneSidedSpring",
    "PreloadedSpring",
    "Prepared",
    "Robot",
    "Scenario",
    "SpringSet",
    "StiffeningSpring",
    "SweepSpec",
    "__version__",
    "animate",
    "codesign",
    "export_html",
    "gait",
    "load",
    "load_design",
    "load_motion",
    "optimal_springs",
    "prepare",
    "run_sweep",
    "transform_motion",
]

_LAZY: dict[str, str] = {
    "DesignChain": "hexaleg.design.chain.chain",
    "DesignParams": "hexaleg.design.chain.config",
    "load_design": "hexaleg.design.chain.design_file",
    "codesign": "hexaleg.design.codesign.build",
    "optimal_springs": "hexaleg.design.search.optimal",
    "load_motion": "hexaleg.motion.recorded.load",
    **dict.fromkeys(("animate", "export_html"), "hexaleg.outputs.viewer.show"),
    "Scenario": "hexaleg.scenario.scenario",
    "run_sweep": "hexaleg.sweep.runner",
    "SweepSpec": "hexaleg.sweep.spec",
}
"""Public names whose modules are imported on first use: the design pulls in the simulation,
the sweep pandas and pyarrow, the viewer meshcat and Pinocchio's visualisers — seconds of import
time that ``import hexaleg`` does not pay."""

_DEPRECATED: dict[str, tuple[str, str, str]] = {
    "tripod_gait": ("hexaleg.motion.legged", "tripod_gait", "hexaleg.gait"),
    "load_robot": ("hexaleg.robot.model", "load_robot",
                   "hexaleg.load (a registered robot or a description TOML), or "
                   "hexaleg.robot.model.load_robot for a bare URDF"),
    "analyze": ("hexaleg.dynamics.prepare", "analyze",
                "hexaleg.prepare(robot, motion, ...).evaluate(springs, objective)"),
    "metrics": ("hexaleg.dynamics.energy", "metrics", "Analysis.metrics"),
    "savings": ("hexaleg.dynamics.energy", "savings", "Analysis.savings"),
    "epsilon": ("hexaleg.dynamics.energy", "epsilon", "hexaleg.dynamics.energy.epsilon"),
    "cost_of_transport": ("hexaleg.dynamics.energy", "cost_of_transport",
                          "Analysis.metrics['cost_of_transport']"),
    "OBJECTIVES": ("hexaleg.dynamics.contact", "OBJECTIVES", "hexaleg.dynamics.contact"),
    "Sinusoid": ("hexaleg.motion.profiles", "Sinusoid", "hexaleg.motion.profiles"),
    "joint_motion": ("hexaleg.motion.joint_motion", "joint_motion", "hexaleg.paper"),
    "CATALOGUE": ("hexaleg.robot.catalogue", "CATALOGUE", "hexaleg.robot.catalogue"),
    "DEFAULT_MOTOR": ("hexaleg.robot.catalogue", "DEFAULT_MOTOR", "hexaleg.robot.catalogue"),
    "motor_from_mapping": ("hexaleg.robot.catalogue", "motor_from_mapping",
                           "a [motor] table of a Scenario"),
    "DESCRIPTIONS": ("hexaleg.robot.registry", "DESCRIPTIONS", "hexaleg.robot.registry"),
    "RobotDescription": ("hexaleg.robot.description", "RobotDescription",
                         "hexaleg.robot.description"),
    "Leg": ("hexaleg.robot.model", "Leg", "Robot.legs"),
    "LegSpec": ("hexaleg.robot.model", "LegSpec", "hexaleg.robot.model"),
    "MotorSet": ("hexaleg.robot.motor_set", "MotorSet", "hexaleg.robot.motor_set"),
    "OptimalSprings": ("hexaleg.design.search.optimal", "OptimalSprings",
                       "optimal_springs' result"),
    "Evaluator": ("hexaleg.design.evaluator", "Evaluator", "hexaleg.design.evaluator"),
    "evaluator": ("hexaleg.design.evaluator", "evaluator", "hexaleg.design.evaluator"),
    "optimise": ("hexaleg.design.studies.optimise", "optimise", "hexaleg.optimal_springs"),
    "placement": ("hexaleg.design.studies.placement", "placement", "hexaleg.optimal_springs"),
    "robustness": ("hexaleg.design.robust.conditions", "robustness", "DesignChain.maps"),
    "robustness_map": ("hexaleg.design.robust.maps", "robustness_map", "DesignChain.maps"),
    "robust_springs": ("hexaleg.design.robust.box", "robust_springs", "DesignChain.robust"),
    "TorsionRequirement": ("hexaleg.design.springs.torsion_spring", "TorsionRequirement",
                           "hexaleg.design.springs.torsion_spring"),
    "design_torsion_spring": ("hexaleg.design.springs.torsion_spring", "design_torsion_spring",
                              "DesignChain's candidates (their parts)"),
    "LoadedDesign": ("hexaleg.design.chain.design_file", "LoadedDesign", "load_design's result"),
    "build_design": ("hexaleg.design.chain.chain", "build_design", "DesignChain(...).run()"),
    "write_design": ("hexaleg.commands.design.write", "write_design", "the hexaleg design "
                     "command, or DesignChain(...).run().to_json()"),
    "ReportConfig": ("hexaleg.report.config", "ReportConfig", "hexaleg.report.config"),
    "build_report": ("hexaleg.report.build", "build_report", "hexaleg.report.build"),
    "write_report": ("hexaleg.commands.report.write", "write_report", "the hexaleg report "
                     "command"),
    "ViewParams": ("hexaleg.outputs.viewer.show", "ViewParams", "hexaleg.outputs.viewer.show"),
    "serve": ("hexaleg.outputs.viewer.show", "serve", "hexaleg.outputs.viewer.show"),
}
"""Names of the 0.1 surface → (module, attribute, what replaces it): still importable for one
release, with a :class:`DeprecationWarning`."""


def __getattr__(name: str) -> Any:
    """A public name imported on first use (PEP 562), or a deprecated one with its warning."""
    if name in _LAZY:
        return getattr(importlib.import_module(_LAZY[name]), name)
    if name in _DEPRECATED:
        module, attr, instead = _DEPRECATED[name]
        warnings.warn(f"hexaleg.{name} is deprecated and leaves the public surface in the next "
                      f"release: use {instead}", DeprecationWarning, stacklevel=2)
        if name == "build_design":
            return _build_design
        return getattr(importlib.import_module(module), attr)
    raise AttributeError(f"module 'hexaleg' has no attribute {name!r}")


def _build_design(config: Any = None, progress: Any = None) -> Any:
    """``build_design(config, progress)`` of 0.1: ``DesignChain(config, progress).run()``."""
    from hexaleg.design.chain.chain import DesignChain

    return DesignChain(config, progress).run()
