"""hexaleg: whole-robot dynamics and energy analysis of legged robots with nonlinear elastic joints.

The public surface is small: load a robot, make a motion, choose springs, analyse. See README.md.
"""

import importlib.metadata
from typing import TYPE_CHECKING

from hexaleg.dynamics.contact import OBJECTIVES, ContactParams
from hexaleg.dynamics.energy import cost_of_transport, epsilon, metrics, savings
from hexaleg.dynamics.prepare import Analysis, Prepared, analyze, prepare
from hexaleg.errors import HexalegError
from hexaleg.motion.joint_motion import joint_motion
from hexaleg.motion.legged import gait, tripod_gait
from hexaleg.motion.params import GaitParams
from hexaleg.motion.profiles import Sinusoid
from hexaleg.motion.trajectory import Motion
from hexaleg.motion.transform import transform_motion
from hexaleg.robot.catalogue import CATALOGUE, DEFAULT_MOTOR, motor_from_mapping
from hexaleg.robot.description import RobotDescription
from hexaleg.robot.model import Leg, LegSpec, Robot, load_robot
from hexaleg.robot.motor import Motor
from hexaleg.robot.motor_set import MotorSet
from hexaleg.robot.registry import DESCRIPTIONS, load
from hexaleg.robot.springs import (
    DeadZoneSpring,
    LinearSpring,
    OneSidedSpring,
    PreloadedSpring,
    SpringSet,
    StiffeningSpring,
)

if TYPE_CHECKING:  # the names __getattr__ imports on first use, for type checkers and the docs
    from hexaleg.design.codesign import OptimalSprings, optimal_springs
    from hexaleg.design.evaluator import Evaluator, RunSpec, evaluator
    from hexaleg.design.optimise import optimise
    from hexaleg.design.placement import placement
    from hexaleg.design.robust import robust_springs
    from hexaleg.design.robustness import robustness
    from hexaleg.design.robustness_map import robustness_map
    from hexaleg.design.torsion_spring import TorsionRequirement, design_torsion_spring
    from hexaleg.motion.recorded.load import load_motion
    from hexaleg.studies.codesign.build import codesign
    from hexaleg.studies.design.build import build_design
    from hexaleg.studies.design.config import DesignConfig
    from hexaleg.studies.design.load import LoadedDesign, load_design
    from hexaleg.studies.design.write import write_design
    from hexaleg.studies.report.build import build_report
    from hexaleg.studies.report.config import ReportConfig
    from hexaleg.studies.report.write import write_report
    from hexaleg.studies.sweep.runner import run_sweep
    from hexaleg.studies.sweep.spec import SweepSpec
    from hexaleg.studies.view import ViewParams, animate, export_html, serve

__version__ = importlib.metadata.version("hexaleg")
"""The installed distribution's version (one source: ``pyproject.toml``)."""

__all__ = [
    "CATALOGUE",
    "DEFAULT_MOTOR",
    "DESCRIPTIONS",
    "OBJECTIVES",
    "Analysis",
    "ContactParams",
    "DeadZoneSpring",
    "DesignConfig",
    "Evaluator",
    "GaitParams",
    "HexalegError",
    "Leg",
    "LegSpec",
    "LinearSpring",
    "LoadedDesign",
    "Motion",
    "Motor",
    "MotorSet",
    "OneSidedSpring",
    "OptimalSprings",
    "PreloadedSpring",
    "Prepared",
    "ReportConfig",
    "Robot",
    "RobotDescription",
    "RunSpec",
    "Sinusoid",
    "SpringSet",
    "StiffeningSpring",
    "SweepSpec",
    "TorsionRequirement",
    "ViewParams",
    "__version__",
    "analyze",
    "animate",
    "build_design",
    "build_report",
    "codesign",
    "cost_of_transport",
    "design_torsion_spring",
    "epsilon",
    "evaluator",
    "export_html",
    "gait",
    "joint_motion",
    "load",
    "load_design",
    "load_motion",
    "load_robot",
    "metrics",
    "motor_from_mapping",
    "optimal_springs",
    "optimise",
    "placement",
    "prepare",
    "robust_springs",
    "robustness",
    "robustness_map",
    "run_sweep",
    "savings",
    "serve",
    "transform_motion",
    "tripod_gait",
    "write_design",
    "write_report",
]

_LAZY: dict[str, str] = {
    "ReportConfig": "hexaleg.studies.report.config",
    "build_report": "hexaleg.studies.report.build",
    "write_report": "hexaleg.studies.report.write",
    **dict.fromkeys(("Evaluator", "RunSpec", "evaluator"), "hexaleg.design.evaluator"),
    "optimise": "hexaleg.design.optimise",
    **dict.fromkeys(("OptimalSprings", "optimal_springs"), "hexaleg.design.codesign"),
    "placement": "hexaleg.design.placement",
    "robustness": "hexaleg.design.robustness",
    "robustness_map": "hexaleg.design.robustness_map",
    "robust_springs": "hexaleg.design.robust",
    **dict.fromkeys(("TorsionRequirement", "design_torsion_spring"),
                    "hexaleg.design.torsion_spring"),
    "load_motion": "hexaleg.motion.recorded.load",
    "codesign": "hexaleg.studies.codesign.build",
    "DesignConfig": "hexaleg.studies.design.config",
    "build_design": "hexaleg.studies.design.build",
    "write_design": "hexaleg.studies.design.write",
    **dict.fromkeys(("LoadedDesign", "load_design"), "hexaleg.studies.design.load"),
    "SweepSpec": "hexaleg.studies.sweep.spec",
    "run_sweep": "hexaleg.studies.sweep.runner",
    **dict.fromkeys(("ViewParams", "animate", "export_html", "serve"), "hexaleg.studies.view"),
}
"""Public names whose modules are imported on first use: the report pulls in matplotlib and
Jinja2, the sweep pandas and pyarrow, the viewer meshcat and Pinocchio's visualisers — seconds of
import time that ``import hexaleg`` does not pay."""


def __getattr__(name: str) -> object:
    """Import a study's module on first use of one of its public names (PEP 562)."""
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'hexaleg' has no attribute {name!r}")
    import importlib

    return getattr(importlib.import_module(module), name)
