"""hexaleg: whole-robot dynamics and energy analysis of legged robots with nonlinear elastic joints.

The public surface is small: load a robot, make a motion, choose springs, analyse. See README.md.
"""

from hexaleg.errors import HexalegError
from hexaleg.robot import Leg, Robot, load_robot
from hexaleg.springs import DeadZoneSpring, SpringSet

__version__ = "0.1.0"

__all__ = [
    "DeadZoneSpring",
    "HexalegError",
    "Leg",
    "Robot",
    "SpringSet",
    "__version__",
    "load_robot",
]
