"""hexaleg: whole-robot dynamics and energy analysis of legged robots with nonlinear elastic joints.

The public surface is small: load a robot, make a motion, choose springs, analyse. See README.md.
"""

from hexaleg.errors import HexalegError
from hexaleg.gait import GaitParams, Sinusoid, joint_motion, transform_motion, tripod_gait
from hexaleg.robot import Leg, Robot, load_robot
from hexaleg.springs import DeadZoneSpring, SpringSet

__version__ = "0.1.0"

__all__ = [
    "DeadZoneSpring",
    "GaitParams",
    "HexalegError",
    "Leg",
    "Robot",
    "Sinusoid",
    "SpringSet",
    "__version__",
    "joint_motion",
    "load_robot",
    "transform_motion",
    "tripod_gait",
]
