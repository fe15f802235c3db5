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
from hexaleg.robot import Leg, Robot, load_robot
from hexaleg.springs import DeadZoneSpring, SpringSet

__version__ = "0.1.0"

__all__ = [
    "CATALOGUE",
    "DEFAULT_MOTOR",
    "OBJECTIVES",
    "Analysis",
    "ContactParams",
    "DeadZoneSpring",
    "GaitParams",
    "HexalegError",
    "Leg",
    "Motion",
    "Motor",
    "Prepared",
    "Robot",
    "Sinusoid",
    "SpringSet",
    "__version__",
    "analyze",
    "cost_of_transport",
    "epsilon",
    "joint_motion",
    "load_robot",
    "metrics",
    "motor_from_mapping",
    "prepare",
    "savings",
    "transform_motion",
    "tripod_gait",
]
