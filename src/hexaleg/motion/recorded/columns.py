"""The columns of a motion log: their names, kinds and units, and the :class:`Log` they fill.

Column names (docs/motion.md): ``time``; optional base pose ``base_x, base_y, base_z`` (world,
m) and ``base_qx, base_qy, base_qz, base_qw``; one column per actuated joint named as the robot's
joints (rad); optional ``contact_<LEG>`` (0/1, a contact switch's: a foot that touches) or
``stance_<LEG>`` (0/1, a plan's: the feet that carry the motion, as hexaleg writes a motion);
optional exact derivatives ``v_<name>`` and
``a_<name>`` of every joint and of the base (LOCAL frame, Pinocchio's free-flyer convention);
optional actuator measurements per joint (:data:`MEASURED`): ``current_<joint>`` (A),
``torque_<joint>`` (output torque, N·m) and ``power_<joint>`` (electrical power, W), which
:func:`hexaleg.motion.recorded.load.load_motion` carries through the cycle for the actuator's
identification (:mod:`hexaleg.dynamics.identification`).
Each name has a kind (:func:`column_kind`) and the kind the units it may be given in
(:data:`UNITS`). Both readers fill a :class:`Log` in SI: CSV and NPZ
(:mod:`hexaleg.motion.recorded.read`) and ROS 2 bags (:mod:`hexaleg.motion.recorded.bag`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from hexaleg.errors import UnknownNameError
from hexaleg.robot.model import Robot
from hexaleg.units import DEG, MM

MAX_LOG_BYTES = 512 * 1024**2
"""Largest log file read, B: a 10-minute log of 30 columns at 1 kHz is about 250 MB of CSV."""

BASE_POSITION = ("base_x", "base_y", "base_z")
BASE_QUATERNION = ("base_qx", "base_qy", "base_qz", "base_qw")
MEASURED: tuple[str, ...] = ("current", "torque", "power")
"""The actuator measurements a log may hold per joint, as ``<kind>_<joint>`` columns: the
current (A), the output torque (N·m) and the electrical power (W); each a kind of :data:`UNITS`."""
def contact_columns(robot: Robot) -> list[str]:
    """The contact switches' columns of ``robot``'s legs, ``contact_<LEG>``."""
    return [f"contact_{leg}" for leg in robot.leg_names]


def stance_columns(robot: Robot) -> list[str]:
    """The planned stance's columns of ``robot``'s legs, ``stance_<LEG>``."""
    return [f"stance_{leg}" for leg in robot.leg_names]


BASE_VELOCITY = ("base_x", "base_y", "base_z", "base_rx", "base_ry", "base_rz")
"""Names of the base's six generalised-velocity components after ``v_``/``a_`` (LOCAL frame)."""

UNITS: dict[str, dict[str, float]] = {
    "time": {"s": 1.0, "ms": 1e-3, "us": 1e-6},
    "length": {"m": 1.0, "cm": 10 * MM, "mm": MM},
    "angle": {"rad": 1.0, "deg": DEG},
    "one": {"": 1.0, "1": 1.0},
    "speed": {"m/s": 1.0, "mm/s": MM},
    "rate": {"rad/s": 1.0, "deg/s": DEG},
    "acceleration": {"m/s^2": 1.0, "mm/s^2": MM},
    "angular acceleration": {"rad/s^2": 1.0, "deg/s^2": DEG},
    "current": {"A": 1.0, "mA": 1e-3},
    "torque": {"N*m": 1.0, "Nm": 1.0, "N·m": 1.0, "N*mm": 1e-3, "Nmm": 1e-3, "N·mm": 1e-3},
    "power": {"W": 1.0, "mW": 1e-3},
}
"""Units allowed per kind of column → their factor to SI (the first of each is the default)."""


@dataclass(frozen=True, eq=False)
class Log:
    """A motion log in SI, as read: not yet resampled or checked beyond its names.

    Attributes:
        t: Time stamps, shape (N,), s, as logged.
        columns: Column name (without unit) → values, each shape (N,), SI (NaN where missing).
        units: Column name → the unit the file gave (the default when none was given).
        path: The file read.
    """

    t: np.ndarray
    columns: dict[str, np.ndarray]
    units: dict[str, str] = field(default_factory=dict)
    path: str = ""

    def has(self, names: tuple[str, ...] | list[str]) -> bool:
        """Whether every name is a column."""
        return all(n in self.columns for n in names)

    def matrix(self, names: tuple[str, ...] | list[str]) -> np.ndarray:
        """The named columns stacked, shape (N, len(names))."""
        return np.stack([self.columns[n] for n in names], axis=1) if names else \
            np.zeros((len(self.t), 0))


def column_kind(robot: Robot, name: str) -> str:
    """The kind of column ``name`` (a key of :data:`UNITS`) for ``robot``.

    Raises:
        UnknownNameError: not a column of a log of ``robot``; the message lists the valid names
            (the robot's joints among them).
    """
    joints = set(robot.joint_names)
    if name == "time":
        return "time"
    if name in BASE_POSITION:
        return "length"
    if name in BASE_QUATERNION or name in contact_columns(robot) or \
            name in stance_columns(robot):
        return "one"
    if name in joints:
        return "angle"
    for kind in MEASURED:
        if name.startswith(f"{kind}_") and name.removeprefix(f"{kind}_") in joints:
            return kind
    for prefix, kinds in (("v_", ("speed", "rate")),
                          ("a_", ("acceleration", "angular acceleration"))):
        base = name.removeprefix(prefix)
        if name.startswith(prefix) and (base in joints or base in BASE_VELOCITY):
            return kinds[0] if base in BASE_POSITION else kinds[1]
    valid = ["time", *BASE_POSITION, *BASE_QUATERNION, *robot.joint_names,
             *contact_columns(robot), *stance_columns(robot), "v_<joint or base>",
             "a_<joint or base>", *(f"{kind}_<joint>" for kind in MEASURED)]
    raise UnknownNameError(f"column of a {robot.name} motion log", name, valid)
