"""How to load one legged robot: which URDF, which SRDF pose is "standing", which joints make a leg.

A :class:`RobotDescription` says declaratively how to load one robot into hexaleg — in the style
of the loaders of example-robot-data (``example_robot_data.robots_loader``) and of
robot_descriptions: the URDF and SRDF files, the SRDF ``group_state`` (or joint values) that is
the robot's standing pose, one :class:`~hexaleg.robot.model.LegSpec` per leg (joints from the body
out and the foot frame), the names of the joint classes (``("haa", "hfe", "kfe")``), the class the
paper's spring goes on by default, and overrides of the gait parameters suited to the robot's
size (plain values; :func:`hexaleg.motion.scaling.robot_gait` makes the parameters).
:meth:`RobotDescription.load` turns it into a :class:`~hexaleg.robot.model.Robot`;
:meth:`RobotDescription.from_toml` reads one's own robot from a TOML file. The registered robots
are in :mod:`hexaleg.robot.registry`.

Legs get hexaleg's canonical names whatever the URDF calls them (``LF RF LH RH`` for the
quadrupeds), so leg groups mean the same on every robot. The standing pose is also stored as
``"stand"``, the pose :mod:`hexaleg.motion.legged` takes its footholds and body height from.

Where the files come from (hexaleg's own, the installed example-robot-data, paths as given) is
:mod:`hexaleg.robot.sources`; the TOML file's format and its parsing,
:mod:`hexaleg.robot.description_file`.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import pinocchio as pin

from hexaleg.checks import real
from hexaleg.config import from_mapping
from hexaleg.errors import InvalidParameterError, UnknownNameError
from hexaleg.robot import fields
from hexaleg.robot.description_file import description_table
from hexaleg.robot.fields import FrozenTable, check_stand, heading, plain
from hexaleg.robot.model import AUTO, LegSpec, Robot, load_robot
from hexaleg.robot.root import check_root
from hexaleg.robot.soles import Sole, flat_stand, sole_of
from hexaleg.robot.sources import EXAMPLE_ROBOT_DATA, FILES, SOURCES, source_dir
from hexaleg.robot.sphere_feet import settle_sphere_feet

if TYPE_CHECKING:
    from hexaleg.robot.actuator import Actuator

_FOUND_LEGS: dict[tuple[str, str, tuple[float, float, float]], tuple[str, ...]] = {}
"""Leg names found in a URDF per (name, URDF path, heading), for
:meth:`RobotDescription.leg_names`."""
_PLANAR_LEGS: dict[tuple[str, str, tuple[float, float, float]], bool] = {}
"""Whether every leg has two joints, per (name, URDF path, heading), for
:meth:`RobotDescription.planar_legs`."""

STAND = "stand"
"""The pose name :mod:`hexaleg.motion.legged` uses for footholds and body height."""


@dataclass(frozen=True)
class RobotDescription:
    """How to load one legged robot (paths, standing pose, legs, joint classes, default gait).

    Attributes:
        name: Registry name, e.g. ``"solo12"``; the loaded robot's name.
        urdf: URDF path relative to the source's directory
            (:func:`hexaleg.robot.sources.source_dir`: ``hexaleg.robot.model.URDF_DIR``,
            example-robot-data's ``share/example-robot-data/robots``, or as given for
            :data:`~hexaleg.robot.sources.FILES`).
        title: Human-readable name and maker (default: the name).
        source: Where the files come from: :data:`~hexaleg.robot.sources.BUILTIN`,
            :data:`~hexaleg.robot.sources.EXAMPLE_ROBOT_DATA` or
            :data:`~hexaleg.robot.sources.FILES` (default).
        srdf: SRDF path relative to the same directory, or None.
        stand: The standing pose: the name of an SRDF ``group_state`` (e.g. ``"standing"``);
            joint name → angle (rad), leg joints not named at Pinocchio's neutral value; or
            ``{"body_height": h, "feet": {leg: [x, y]}, "joints": {joint: angle}}`` (m, base
            frame; ``feet`` and ``joints`` optional), the legs solved by
            :func:`hexaleg.robot.stand.stand_from_feet`. A joint on no leg (an arm's, a
            torso's) not given is held at its zero clipped into its URDF limits
            (:func:`hexaleg.robot.stand.hold_other_joints`). None: the SRDF's
            ``standing`` state if it has one, else the zero configuration (with a note).
        legs: One spec per leg, with hexaleg's leg names (``LF RF LH RH`` …); None finds them
            from the kinematic tree (:mod:`hexaleg.robot.discover`).
        joint_kinds: Names of the joint classes, one per joint of a leg from the body out; None
            for the found (or hexaleg's) names.
        spring_class: The joint class the springs go on by default (the knees of the
            quadrupeds; the femur, as in the paper, for hexaleg); None for the second joint of
            a leg (the paper's "second joint"), see :meth:`spring_class_of`.
        gait: The robot's default gait as overrides of
            :class:`~hexaleg.motion.params.GaitParams` (field name → plain value, leg groups
            as tuples of leg names), sized to the robot; a read-only mapping. Keys are
            checked by ``robot_gait``, the leg names of ``groups`` here.
        notes: Where the description's facts come from.
        motor: The robot's actuators from :data:`hexaleg.robot.catalogue.CATALOGUE`: one name for
            every joint, or a table joint class → name (``{femur = "XM430-W350", …}``; classes
            not named get a generic actuator); None when the catalogue has none (then
            :meth:`actuator` builds one per class from the URDF limits).
        mesh_dirs: Where ``package://`` mesh URIs resolve, for
            :data:`~hexaleg.robot.sources.FILES` (the other sources know their own).
        heading: The base axis that points forward, ``[x, y, 0]`` (:attr:`Robot.heading`).
        max_outer_diameter: Joint class → largest outer diameter of a spring on its joints, m;
            default the links' width (:func:`hexaleg.design.springs.parts.spring_outer_diameter`).
        arbor_diameter: Joint class → diameter of the shaft or hub a spring on its joints winds
            on, m (0: none); default the servo's output hub, else a rule from the links' width
            (:func:`hexaleg.design.springs.parts.arbor_for`).
        inertias: What loading does with impossible link inertias (:mod:`hexaleg.robot.
            inertials`): ``"refuse"`` (default), ``"repair"`` (a stated box rule) or ``"keep"``.
        root_offset: Where the base frame goes, ``[x, y, z]`` m in the URDF root link's frame
            (:mod:`hexaleg.robot.root`: for a root link below the feet; stated in the notes);
            None keeps the root link's origin.
        electronics_power: What the robot draws besides its joint actuators (computer,
            sensors, radios, converters), W (≥ 0); None: not known, and the whole draw
            (:mod:`hexaleg.dynamics.draw`) says it leaves it out.
        battery_wh: The battery's energy as printed on it, Wh (> 0); the whole draw gives the
            hours it lasts. None: no battery named.
        moves: Joint on no leg (an arm's, a torso's, a head's) → ``{amplitude, phase}`` (rad):
            the joint swings ``q = q_stand + amplitude · sin(2π t / T + phase)`` over every
            gait cycle of period ``T`` instead of being held at the stand
            (:attr:`Robot.moves <hexaleg.robot.loaded.Robot.moves>`); its torque and energy
            are counted by its own actuator and its inertia carried by the dynamics. Checked
            on loading: a joint on no leg, within its limits over the swing.
        sole: ``[length, width]`` m: every foot is a flat sole of that size centred on its
            foot frame (:mod:`hexaleg.robot.soles`), laid flat in the stand; None (default):
            point feet.
    """

    name: str
    urdf: str
    title: str = ""
    source: str = FILES
    srdf: str | None = None
    stand: str | Mapping[str, Any] | None = None
    legs: tuple[LegSpec, ...] | None = None
    joint_kinds: tuple[str, ...] | None = None
    spring_class: str | None = None
    gait: Mapping[str, Any] = field(default_factory=lambda: FrozenTable({}))
    notes: str = ""
    motor: str | Mapping[str, str] | None = None
    mesh_dirs: tuple[str, ...] = ()
    heading: tuple[float, float, float] = (1.0, 0.0, 0.0)
    max_outer_diameter: Mapping[str, float] = field(default_factory=lambda: FrozenTable({}))
    arbor_diameter: Mapping[str, float] = field(default_factory=lambda: FrozenTable({}))
    inertias: str = "refuse"
    root_offset: tuple[float, float, float] | None = None
    electronics_power: float | None = None
    battery_wh: float | None = None
    moves: Mapping[str, Any] = field(default_factory=lambda: FrozenTable({}))
    sole: Sole | Sequence[float] | None = None

    def __post_init__(self) -> None:
        if self.source not in SOURCES:
            raise UnknownNameError("robot file source", self.source, SOURCES)
        for key in ("name", "urdf"):
            if not isinstance(getattr(self, key), str) or not getattr(self, key):
                raise InvalidParameterError(f"robot.{key}", getattr(self, key), "a non-empty "
                                            "string")
        if self.srdf == "":
            raise InvalidParameterError(f"{self.name}: srdf", "", "an SRDF file, or leave the "
                                        "key out")
        object.__setattr__(self, "title", self.title or self.name)
        if self.legs is not None:
            if not self.legs:
                raise InvalidParameterError(f"{self.name}: legs", self.legs,
                                            "at least one LegSpec, or none given to find them")
            object.__setattr__(self, "legs", tuple(self.legs))
        if self.joint_kinds is not None:
            object.__setattr__(self, "joint_kinds", tuple(self.joint_kinds))
            for leg in self.legs or ():
                if len(leg.joints) != len(self.joint_kinds):
                    raise InvalidParameterError(
                        f"{self.name}: leg {leg.name} joints", leg.joints,
                        f"{len(self.joint_kinds)} joints, one per kind {self.joint_kinds}")
            if self.spring_class is not None and self.spring_class not in self.joint_kinds:
                raise UnknownNameError("joint class", self.spring_class, self.joint_kinds)
        if self.motor is not None:
            object.__setattr__(self, "motor", self._check_motor(self.motor))
        if not isinstance(self.gait, Mapping) or not all(isinstance(k, str) for k in self.gait):
            raise InvalidParameterError(f"{self.name}: gait", self.gait,
                                        "a table of GaitParams keys and values")
        object.__setattr__(self, "gait", FrozenTable({k: plain(v) for k, v in self.gait.items()}))
        if "groups" in self.gait and self.legs is not None:
            self.check_groups(self.gait["groups"])
        object.__setattr__(self, "stand", check_stand(self.name, self.stand))
        object.__setattr__(self, "mesh_dirs", tuple(self.mesh_dirs))
        if self.root_offset is not None:
            object.__setattr__(self, "root_offset", fields.vector3(
                f"{self.name}: root_offset", self.root_offset, "m, in the URDF root link's frame"))
        object.__setattr__(self, "heading", heading(self.name, self.heading))
        if self.electronics_power is not None:
            object.__setattr__(self, "electronics_power", real(
                f"{self.name}: electronics_power", self.electronics_power, low=0.0,
                allowed="a power ≥ 0 W, or leave the key out (not known)"))
        if self.battery_wh is not None:
            object.__setattr__(self, "battery_wh", real(
                f"{self.name}: battery_wh", self.battery_wh, low=0.0, low_open=True,
                allowed="the battery's energy > 0 Wh, or leave the key out (no battery)"))
        object.__setattr__(self, "moves", fields.moves_table(self.name, self.moves))
        if self.sole is not None:
            object.__setattr__(self, "sole", sole_of(self.name, self.sole))
        object.__setattr__(self, "max_outer_diameter", fields.diameters_table(
            self.name, self.joint_kinds, self.max_outer_diameter))
        object.__setattr__(self, "arbor_diameter", fields.diameters_table(
            self.name, self.joint_kinds, self.arbor_diameter, "arbor_diameter", low_open=False))

    def _check_motor(self, motor: Any) -> str | Mapping[str, str]:
        from hexaleg.robot.catalogue import CATALOGUE

        names = motor.values() if isinstance(motor, Mapping) else [motor]
        for name in names:
            if not isinstance(name, str) or name not in CATALOGUE:
                raise UnknownNameError(f"{self.name}: motor", name, CATALOGUE)
        if isinstance(motor, Mapping):
            if not motor:
                raise InvalidParameterError(f"{self.name}: motor", "{}", "a catalogue name, or "
                                            "a table joint class → catalogue name")
            return FrozenTable(dict(motor))  # its classes are checked against the robot's
            # (its leg classes and the joints on no leg) when the actuators are built
        return str(motor)

    def actuator(self, robot: Robot) -> Actuator:
        """The robot's actuators, and so the analysis' torque limits (each joint's stall torque):
        :attr:`motor` per joint class, a generic actuator from the URDF limits for a class
        without one (:func:`hexaleg.robot.motor_set.class_motors`).

        Args:
            robot: The loaded robot (its joint classes and URDF limits).

        Returns:
            The motor of every joint, or the motor set when the classes' motors differ.

        Raises:
            UnknownNameError: the motor table names a class the robot does not have.
            InvalidParameterError: a class without a catalogue motor whose URDF joints have no
                effort or velocity limit (names the value; give ``motor = "…"`` instead).
        """
        from hexaleg.robot.catalogue import CATALOGUE
        from hexaleg.robot.motor_set import class_motors

        if isinstance(self.motor, str):
            return CATALOGUE[self.motor]
        named = {kind: CATALOGUE[name] for kind, name in (self.motor or {}).items()}
        return class_motors(robot, named, f"generic ({self.name} URDF limits)")

    def spring_class_of(self, robot: Robot) -> str:
        """The class the springs go on by default: :attr:`spring_class`, else the loaded robot's
        second joint class (the paper's "second joint"; the only one of one-joint legs)."""
        return self.spring_class or robot.joint_kinds[min(1, len(robot.joint_kinds) - 1)]

    def leg_names(self) -> tuple[str, ...]:
        """The robot's leg names: from :attr:`legs`, else found in the URDF (the robot is
        loaded once per process for that, :mod:`hexaleg.robot.discover`)."""
        if self.legs is not None:
            return tuple(leg.name for leg in self.legs)
        key = (self.name, str(self.urdf_path), self.heading)
        if key not in _FOUND_LEGS:
            _FOUND_LEGS[key] = self.load().leg_names
        return _FOUND_LEGS[key]

    def planar_legs(self) -> bool:
        """Whether every leg has two joints, moving its foot in a plane (from :attr:`legs`,
        else the robot is loaded once per process for that)."""
        if self.legs is not None:
            return all(len(leg.joints) == 2 for leg in self.legs)
        key = (self.name, str(self.urdf_path), self.heading)
        if key not in _PLANAR_LEGS:
            _PLANAR_LEGS[key] = all(len(leg.joint_names) == 2 for leg in self.load().legs)
        return _PLANAR_LEGS[key]

    def check_groups(self, groups: Any) -> None:
        """Check that gait leg groups hold every leg of this robot exactly once.

        Args:
            groups: Leg groups, a sequence of sequences of leg names.

        Raises:
            InvalidParameterError: a leg is missing, repeated or not one of the robot's.
        """
        names = set(self.leg_names())
        try:
            grouped = sorted(leg for group in groups for leg in group)
        except TypeError:  # not groups of names: reported below
            grouped = None
        if grouped != sorted(names):
            raise InvalidParameterError(f"{self.name}: gait.groups", groups,
                                        f"every leg of {sorted(names)} in exactly one group")

    @classmethod
    def from_toml(cls, path: str | Path) -> RobotDescription:
        """A description of one's own robot from the ``[robot]`` table of a TOML file
        (:func:`read_description`: the format and its errors)."""
        return read_description(path)

    @property
    def urdf_path(self) -> Path:
        """The URDF file, resolved in the installed source."""
        return source_dir(self.source) / self.urdf

    @property
    def srdf_path(self) -> Path | None:
        """The SRDF file, resolved in the installed source, or None."""
        return None if self.srdf is None else source_dir(self.source) / self.srdf

    @property
    def package_dirs(self) -> tuple[Path, ...]:
        """Where ``package://`` mesh URIs resolve: the URDFs of example-robot-data name meshes
        ``package://example-robot-data/robots/…``, so the directory holding
        ``example-robot-data/``; :attr:`mesh_dirs` for :data:`~hexaleg.robot.sources.FILES`."""
        if self.source == EXAMPLE_ROBOT_DATA:
            return (source_dir(self.source).parent.parent,)
        return tuple(Path(d) for d in self.mesh_dirs)

    def load(self) -> Robot:
        """Load the robot: Pinocchio model with a free-flyer base, legs, poses.

        Every pose gets the base at the origin with identity orientation (the SRDFs of
        example-robot-data put the base at the standing height), and the standing pose is also
        stored as ``"stand"``.

        Returns:
            The robot; ``robot.joint_kinds`` is :attr:`joint_kinds`.

        Raises:
            RobotModelError: files missing or malformed, a leg joint or foot frame not in the
                URDF (the message lists the frames found), or the base origin below the feet
                in the stand pose (:func:`hexaleg.robot.root.check_root`: names the fix).
            UnknownNameError: the standing pose names an SRDF group_state or joint that does not
                exist (the message lists the valid ones).
        """
        robot = load_robot(self.urdf_path, self.srdf_path,
                           legs=self.legs if self.legs is not None else AUTO,
                           package_dirs=self.package_dirs, joint_kinds=self.joint_kinds,
                           heading=self.heading, inertias=self.inertias,
                           root_offset=self.root_offset)
        robot.name = self.name
        if self.spring_class is not None and self.spring_class not in robot.joint_kinds:
            raise UnknownNameError("joint class", self.spring_class, robot.joint_kinds)
        base = pin.neutral(robot.model)[:7]
        for q in robot.poses.values():
            q[:7] = base
        try:
            stand, note = self._stand_pose(robot)
        except InvalidParameterError:  # the root below the feet is the cause to name
            if isinstance(self.stand, Mapping) and "body_height" in self.stand:
                check_root(robot, pin.neutral(robot.model), "the zero configuration (the "
                           "stand's feet at body_height below the base cannot be reached)")
            raise
        if robot.foot_spheres:  # round feet touch at their lowest point in this stand
            solved = isinstance(self.stand, Mapping) and "body_height" in self.stand
            stand, sphere_note = settle_sphere_feet(
                robot, stand, (lambda: self._stand_pose(robot)[0]) if solved else None)
            robot.notes = (*robot.notes, sphere_note)
        if isinstance(self.sole, Sole):
            robot.soles = {leg.name: self.sole for leg in robot.legs}
            stand = flat_stand(robot, stand, tuple(robot.soles))
        check_root(robot, stand, "the stand pose")
        robot.poses[STAND] = stand
        from hexaleg.robot.stand import checked_moves

        robot.moves = checked_moves(self.name, robot, stand, self.moves)
        if note:
            robot.notes = (*robot.notes, note)
        return robot

    def _stand_pose(self, robot: Robot) -> tuple[np.ndarray, str | None]:
        from hexaleg.robot.stand import hold_other_joints, stand_from_feet

        if self.stand is None:
            if "standing" in robot.poses:
                return robot.pose("standing"), None
            return hold_other_joints(robot, pin.neutral(robot.model), {}), (
                "no stand given and no SRDF 'standing' state: standing at the zero "
                "configuration; give stand = {body_height = …} to stand on bent legs")
        if isinstance(self.stand, str):
            return robot.pose(self.stand), None
        if "body_height" in self.stand:
            q = hold_other_joints(robot, pin.neutral(robot.model), self.stand.get("joints", {}))
            return stand_from_feet(robot, self.stand["body_height"], self.stand.get("feet"),
                                   q), None
        return hold_other_joints(robot, pin.neutral(robot.model), self.stand,
                                 legs_too=True), None


def read_description(path: str | Path) -> RobotDescription:
    """A description of one's own robot from the ``[robot]`` table of a TOML file: the table
    parsed (:func:`hexaleg.robot.description_file.description_table`: the format, relative paths
    relative to the file), every value checked by the description.

    Args:
        path: The TOML file.

    Returns:
        The description (its files are not opened until
        :meth:`~hexaleg.robot.description.RobotDescription.load`).

    Raises:
        ConfigError: the file cannot be read, has no ``[robot]`` table, or a value has the wrong
            type.
        UnknownNameError: an unknown key (the message lists the valid keys).
        InvalidParameterError: a value out of range.
    """
    return from_mapping(RobotDescription, *description_table(path))
