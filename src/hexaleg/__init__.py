"""hexaleg: whole-robot dynamics and energy analysis of legged robots with nonlinear elastic joints.

The public surface is small: load a robot, make a motion, choose springs, analyse. See README.md.
"""

from hexaleg.dynamics.energy import cost_of_transport, epsilon, metrics, savings
from hexaleg.dynamics.forces import OBJECTIVES, ContactParams
from hexaleg.dynamics.prepare import Analysis, Prepared, analyze, prepare
from hexaleg.errors import HexalegError
from hexaleg.motion.gait import GaitParams, Sinusoid, joint_motion, transform_motion, tripod_gait
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.model import Leg, LegSpec, Robot, load_robot
from hexaleg.robot.motor import CATALOGUE, DEFAULT_MOTOR, Motor, motor_from_mapping
from hexaleg.robot.registry import DESCRIPTIONS, RobotDescription, load
from hexaleg.robot.springs import DeadZoneSpring, SpringSet

__version__ = "0.1.0"

__all__ = [
    "CATALOGUE",
    "DEFAULT_MOTOR",
    "DESCRIPTIONS",
    "OBJECTIVES",
    "Analysis",
    "ContactParams",
    "DeadZoneSpring",
    "GaitParams",
    "HexalegError",
    "Leg",
    "LegSpec",
    "Motion",
    "Motor",
    "Prepared",
    "ReportConfig",
    "Robot",
    "RobotDescription",
    "RunSpec",
    "Sinusoid",
    "SpringSet",
    "SweepSpec",
    "ViewParams",
    "__version__",
    "analyze",
    "animate",
    "build_report",
    "cost_of_transport",
    "epsilon",
    "export_html",
    "joint_motion",
    "load",
    "load_robot",
    "metrics",
    "motor_from_mapping",
    "optimise",
    "placement",
    "prepare",
    "robustness",
    "run_sweep",
    "savings",
    "serve",
    "transform_motion",
    "tripod_gait",
    "write_report",
]

_LAZY: dict[str, str] = {
    **dict.fromkeys(("ReportConfig", "build_report", "write_report"),
    "hexaleg.studies.report.build"),
    **dict.fromkeys(("RunSpec", "SweepSpec", "optimise", "placement", "robustness", "run_sweep"),
                    "hexaleg.studies.sweep.runner"),
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
