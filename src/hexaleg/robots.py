"""A registry of legged robots: which URDF, which SRDF pose is "standing", which joints make a leg.

Each :class:`RobotDescription` says declaratively how to load one robot into hexaleg — in the style
of the loaders of example-robot-data (``example_robot_data.robots_loader``) and of
robot_descriptions: the URDF and SRDF files, the SRDF ``group_state`` (or joint values) that is
the robot's standing pose, one :class:`~hexaleg.robot.LegSpec` per leg (joints from the body out
and the foot frame), the names of the joint classes (``("haa", "hfe", "kfe")``), the class the
paper's spring goes on by default, and gait parameters suited to the robot's size. :func:`load`
turns a name into a :class:`~hexaleg.robot.Robot`.

Legs get hexaleg's canonical names whatever the URDF calls them (``LF RF LH RH`` for the
quadrupeds: Solo's ``FL``/``HR`` and Go2's ``FL``/``RR`` become ``LF``/``RH``), so leg groups such
as :data:`TROT` mean the same on every robot. The standing pose is also stored as ``"stand"``, the
pose :mod:`hexaleg.gait` takes its footholds and body height from.

The quadrupeds' files come from the installed ``example-robot-data`` distribution (a cmeel
package without a Python module), located through :mod:`importlib.metadata`, never from the
network.
"""

from __future__ import annotations

import importlib.metadata
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType

import numpy as np
import pinocchio as pin

from hexaleg.errors import InvalidParameterError, RobotModelError, UnknownNameError
from hexaleg.gait import GaitParams
from hexaleg.robot import (
    HEXALEG_LEGS,
    JOINT_KINDS,
    URDF_DIR,
    LegSpec,
    Robot,
    load_robot,
)

BUILTIN = "hexaleg"
"""Files source of the robot shipped with hexaleg (``urdf/hexaleg.urdf`` and ``.srdf``)."""
EXAMPLE_ROBOT_DATA = "example-robot-data"
"""Files source: the installed example-robot-data distribution (paths relative to its
``share/example-robot-data/robots`` directory)."""
SOURCES: tuple[str, ...] = (BUILTIN, EXAMPLE_ROBOT_DATA)

STAND = "stand"
"""The pose name :mod:`hexaleg.gait` uses for footholds and body height."""

TROT: tuple[tuple[str, ...], ...] = (("LF", "RH"), ("RF", "LH"))
"""A quadruped's trot: the diagonal pairs move together, {LF, RH} touching down at t = 0."""


def example_robot_data_dir() -> Path:
    """The ``share/example-robot-data/robots`` directory of the installed example-robot-data.

    Found from the distribution's file list (:func:`importlib.metadata.distribution`), so it does
    not depend on where the package is installed nor on the cmeel prefix's name.

    Raises:
        RobotModelError: example-robot-data is not installed, or its file list has no robots.
    """
    try:
        dist = importlib.metadata.distribution(EXAMPLE_ROBOT_DATA)
    except importlib.metadata.PackageNotFoundError:
        raise RobotModelError("the example-robot-data package is not installed; "
                              "pip install example-robot-data") from None
    for f in dist.files or ():
        parts = f.parts
        for i in range(len(parts) - 2):
            if parts[i:i + 3] == ("share", "example-robot-data", "robots"):
                return Path(dist.locate_file(Path(*parts[:i + 3])))
    raise RobotModelError(f"example-robot-data {dist.version} has no share/example-robot-data/"
                          "robots directory in its file list")


@dataclass(frozen=True)
class RobotDescription:
    """How to load one legged robot (paths, standing pose, legs, joint classes, default gait).

    Attributes:
        name: Registry name, e.g. ``"solo12"``.
        title: Human-readable name and maker.
        source: Where the files come from: :data:`BUILTIN` or :data:`EXAMPLE_ROBOT_DATA`.
        urdf: URDF path relative to the source's directory (``hexaleg.robot.URDF_DIR`` or
            example-robot-data's ``share/example-robot-data/robots``).
        srdf: SRDF path relative to the same directory, or None.
        stand: The standing pose: the name of an SRDF ``group_state`` (e.g. ``"standing"``) or
            joint name → angle (rad); joints not named stay at Pinocchio's neutral value.
        legs: One spec per leg, with hexaleg's leg names (``LF RF LH RH`` …).
        joint_kinds: Names of the joint classes, one per joint of a leg from the body out.
        spring_class: The joint class the springs go on by default (the knees of the
            quadrupeds; the femur, as in the paper, for hexaleg).
        gait: Default gait parameters, sized to the robot (leg groups included).
        notes: Where the description's facts come from.
    """

    name: str
    title: str
    source: str
    urdf: str
    srdf: str | None
    stand: str | Mapping[str, float]
    legs: tuple[LegSpec, ...]
    joint_kinds: tuple[str, ...]
    spring_class: str
    gait: GaitParams = field(default_factory=GaitParams)
    notes: str = ""

    def __post_init__(self) -> None:
        if self.source not in SOURCES:
            raise UnknownNameError("robot file source", self.source, SOURCES)
        if not self.legs:
            raise InvalidParameterError(f"{self.name}: legs", self.legs, "at least one LegSpec")
        object.__setattr__(self, "legs", tuple(self.legs))
        object.__setattr__(self, "joint_kinds", tuple(self.joint_kinds))
        for leg in self.legs:
            if len(leg.joints) != len(self.joint_kinds):
                raise InvalidParameterError(
                    f"{self.name}: leg {leg.name} joints", leg.joints,
                    f"{len(self.joint_kinds)} joints, one per kind {self.joint_kinds}")
        if self.spring_class not in self.joint_kinds:
            raise UnknownNameError("joint class", self.spring_class, self.joint_kinds)
        names = {leg.name for leg in self.legs}
        grouped = [leg for group in self.gait.groups for leg in group]
        if sorted(grouped) != sorted(names):
            raise InvalidParameterError(f"{self.name}: gait.groups", self.gait.groups,
                                        f"every leg of {sorted(names)} in exactly one group")
        if not isinstance(self.stand, str):
            object.__setattr__(self, "stand", MappingProxyType(dict(self.stand)))

    def _dir(self) -> Path:
        return example_robot_data_dir() if self.source == EXAMPLE_ROBOT_DATA else URDF_DIR

    @property
    def urdf_path(self) -> Path:
        """The URDF file, resolved in the installed source."""
        return self._dir() / self.urdf

    @property
    def srdf_path(self) -> Path | None:
        """The SRDF file, resolved in the installed source, or None."""
        return None if self.srdf is None else self._dir() / self.srdf

    @property
    def package_dirs(self) -> tuple[Path, ...]:
        """Where ``package://`` mesh URIs resolve: the URDFs of example-robot-data name meshes
        ``package://example-robot-data/robots/…``, so the directory holding
        ``example-robot-data/``."""
        return (self._dir().parent.parent,) if self.source == EXAMPLE_ROBOT_DATA else ()

    def load(self) -> Robot:
        """Load the robot: Pinocchio model with a free-flyer base, legs, poses.

        Every pose gets the base at the origin with identity orientation (the SRDFs of
        example-robot-data put the base at the standing height), and the standing pose is also
        stored as ``"stand"``.

        Returns:
            The robot; ``robot.joint_kinds`` is :attr:`joint_kinds`.

        Raises:
            RobotModelError: files missing or malformed, or a leg joint or foot frame not in the
                URDF (the message lists the frames found).
            UnknownNameError: the standing pose names an SRDF group_state or joint that does not
                exist (the message lists the valid ones).
        """
        robot = load_robot(self.urdf_path, self.srdf_path, legs=self.legs,
                           package_dirs=self.package_dirs, joint_kinds=self.joint_kinds)
        base = pin.neutral(robot.model)[:7]
        for q in robot.poses.values():
            q[:7] = base
        robot.poses[STAND] = self._stand_pose(robot)
        return robot

    def _stand_pose(self, robot: Robot) -> np.ndarray:
        if isinstance(self.stand, str):
            return robot.pose(self.stand)
        q = pin.neutral(robot.model)
        for joint, value in self.stand.items():
            robot.column(joint)  # an unknown joint raises, listing the joints
            q[robot.model.joints[robot.model.getJointId(joint)].idx_q] = value
        return q


def _legs(prefixes: Mapping[str, str], joints: tuple[str, str, str], foot: str
          ) -> tuple[LegSpec, ...]:
    """Leg specs from the URDF's leg prefixes (hexaleg leg name → URDF prefix) and name patterns
    with ``{p}`` for the prefix, e.g. ``("{p}_HAA", "{p}_HFE", "{p}_KFE")`` and ``"{p}_FOOT"``."""
    return tuple(LegSpec(leg, tuple(j.format(p=p) for j in joints), foot.format(p=p))
                 for leg, p in prefixes.items())


_HAA_HFE_KFE = ("{p}_HAA", "{p}_HFE", "{p}_KFE")

DESCRIPTIONS: Mapping[str, RobotDescription] = MappingProxyType({d.name: d for d in (
    RobotDescription(
        name="hexaleg", title="hexaleg: the switchable hexapod/sphere robot of the paper",
        source=BUILTIN, urdf="hexaleg.urdf", srdf="hexaleg.srdf", stand=STAND,
        legs=HEXALEG_LEGS, joint_kinds=JOINT_KINDS, spring_class="femur", gait=GaitParams(),
        notes="urdf/hexaleg.toml (see docs/robot.md); the paper's spring is at the femur joint"),
    RobotDescription(
        name="solo12", title="Solo-12 (Open Dynamic Robot Initiative)",
        source=EXAMPLE_ROBOT_DATA, urdf="solo_description/robots/solo12.urdf",
        srdf="solo_description/srdf/solo.srdf", stand="standing",
        legs=_legs({"LF": "FL", "RF": "FR", "LH": "HL", "RH": "HR"}, _HAA_HFE_KFE, "{p}_FOOT"),
        joint_kinds=("haa", "hfe", "kfe"), spring_class="kfe",
        gait=GaitParams(period=0.5, duty_factor=0.6, stride_length=0.08, step_height=0.04,
                        groups=TROT),
        notes="example-robot-data solo_description (loader Solo12Loader: robots/solo12.urdf, "
              "srdf/solo.srdf, pose 'standing'); 2.5 kg, thigh and shank 0.16 m"),
    RobotDescription(
        name="anymal", title="ANYmal B (ANYbotics), example-robot-data's 'anymal'",
        source=EXAMPLE_ROBOT_DATA, urdf="anymal_b_simple_description/robots/anymal.urdf",
        srdf="anymal_b_simple_description/srdf/anymal.srdf", stand="standing",
        legs=_legs({leg: leg for leg in ("LF", "RF", "LH", "RH")}, _HAA_HFE_KFE, "{p}_FOOT"),
        joint_kinds=("haa", "hfe", "kfe"), spring_class="kfe",
        gait=GaitParams(period=0.8, duty_factor=0.6, stride_length=0.2, step_height=0.08,
                        groups=TROT),
        notes="example-robot-data anymal_b_simple_description (loader ANYmalLoader); 30.5 kg"),
    RobotDescription(
        name="anymal_c", title="ANYmal C (ANYbotics)",
        source=EXAMPLE_ROBOT_DATA, urdf="anymal_c_simple_description/urdf/anymal.urdf",
        srdf="anymal_c_simple_description/srdf/anymal.srdf", stand="standing",
        legs=_legs({leg: leg for leg in ("LF", "RF", "LH", "RH")}, _HAA_HFE_KFE, "{p}_FOOT"),
        joint_kinds=("haa", "hfe", "kfe"), spring_class="kfe",
        gait=GaitParams(period=0.8, duty_factor=0.6, stride_length=0.2, step_height=0.08,
                        groups=TROT),
        notes="example-robot-data anymal_c_simple_description (loader ANYmalCLoader); 52.1 kg"),
    RobotDescription(
        name="go2", title="Go2 (Unitree)",
        source=EXAMPLE_ROBOT_DATA, urdf="go2_description/urdf/go2.urdf",
        srdf="go2_description/srdf/go2.srdf", stand="standing",
        legs=_legs({"LF": "FL", "RF": "FR", "LH": "RL", "RH": "RR"},
                   ("{p}_hip_joint", "{p}_thigh_joint", "{p}_calf_joint"), "{p}_foot"),
        joint_kinds=("hip", "thigh", "knee"), spring_class="knee",
        gait=GaitParams(period=0.6, duty_factor=0.6, stride_length=0.12, step_height=0.06,
                        groups=TROT),
        notes="example-robot-data go2_description (loader Go2Loader); 16.1 kg; the knee class "
              "is the URDF's calf joints"),
)})
"""The registered robots by name; :data:`DEFAULT_ROBOT` first."""

DEFAULT_ROBOT = "hexaleg"


def description(name: str = DEFAULT_ROBOT) -> RobotDescription:
    """The registered description called ``name``.

    Raises:
        UnknownNameError: no such robot; the message lists the registered names.
    """
    if not isinstance(name, str) or name not in DESCRIPTIONS:
        raise UnknownNameError("robot", name, DESCRIPTIONS)
    return DESCRIPTIONS[name]


def load(name: str = DEFAULT_ROBOT) -> Robot:
    """Load a registered robot by name (``"hexaleg"``, ``"solo12"``, ``"anymal"``, …).

    Args:
        name: A key of :data:`DESCRIPTIONS`.

    Returns:
        The robot, with the standing pose as ``"stand"`` (see :meth:`RobotDescription.load`).

    Raises:
        UnknownNameError: no such robot; the message lists the registered names.
        RobotModelError: the robot's files cannot be found or loaded.
    """
    return description(name).load()
