"""hexaleg: whole-robot dynamics and energy analysis of legged robots with nonlinear elastic joints.

The public surface is small: load a robot, make a motion, choose springs, analyse. See README.md.
"""

from hexaleg.energy import cost_of_transport, epsilon, metrics, savings
from hexaleg.errors import HexalegError
from hexaleg.gait import GaitParams, Sinusoid, joint_motion, transform_motion, tripod_gait
from hexaleg.motor import CATALOGUE, DEFAULT_MOTOR, Motor, motor_from_mapping
from hexaleg.robot import Leg, Robot, load_robot
from hexaleg.springs import DeadZoneSpring, SpringSet

__version__ = "0.1.0"

__all__ = [
    "CATALOGUE",
    "DEFAULT_MOTOR",
    "DeadZoneSpring",
    "GaitParams",
    "HexalegError",
    "Leg",
    "Motor",
    "Robot",
    "Sinusoid",
    "SpringSet",
    "__version__",
    "cost_of_transport",
    "epsilon",
    "joint_motion",
    "load_robot",
    "metrics",
    "motor_from_mapping",
    "savings",
    "transform_motion",
    "tripod_gait",
]
