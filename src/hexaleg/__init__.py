"""hexaleg: whole-robot dynamics and energy analysis of legged robots with nonlinear elastic joints.

The public surface is small: load a robot, make a motion, choose springs, analyse. See README.md.
"""

from hexaleg.analysis import Analysis, Prepared, analyze, prepare
from hexaleg.energy import cost_of_transport, epsilon, metrics, savings
from hexaleg.errors import HexalegError
from hexaleg.forces import OBJECTIVES, ContactParams
from hexaleg.gait import GaitParams, Sinusoid, joint_motion, transform_motion, tripod_gait
from hexaleg.motion import Motion
from hexaleg.motor import CATALOGUE, DEFAULT_MOTOR, Motor, motor_from_mapping
from hexaleg.report import ReportConfig, build_report, write_report
from hexaleg.robot import Leg, LegSpec, Robot, load_robot
from hexaleg.robots import DESCRIPTIONS, RobotDescription, load
from hexaleg.springs import DeadZoneSpring, SpringSet
from hexaleg.sweep import RunSpec, SweepSpec, optimise, placement, robustness, run_sweep

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

_VIEW = ("ViewParams", "animate", "export_html", "serve")


def __getattr__(name: str) -> object:
    """Import the browser viewer (:mod:`hexaleg.view`) on first use: it pulls in meshcat and
    Pinocchio's visualisers, which take seconds to import."""
    if name in _VIEW:
        from hexaleg import view

        return getattr(view, name)
    raise AttributeError(f"module 'hexaleg' has no attribute {name!r}")
