"""The registry of legged robots: hexaleg and the quadrupeds of example-robot-data, by name.

:data:`DESCRIPTIONS` holds one :class:`~hexaleg.robot.description.RobotDescription` per robot;
:func:`description` and :func:`load` turn a name (or the path of one's own robot's TOML
description) into the description or the loaded :class:`~hexaleg.robot.model.Robot`.

Legs get hexaleg's canonical names whatever the URDF calls them (``LF RF LH RH`` for the
quadrupeds: Solo's ``FL``/``HR`` and Go2's ``FL``/``RR`` become ``LF``/``RH``), so leg groups such
as :data:`TROT` mean the same on every robot.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from pathlib import Path
from types import MappingProxyType

from hexaleg.checks import typed
from hexaleg.errors import InvalidParameterError, UnknownNameError
from hexaleg.robot.description import STAND, RobotDescription
from hexaleg.robot.model import HEXALEG_LEGS, JOINT_KINDS, LegSpec, Robot
from hexaleg.robot.sources import BUILTIN, EXAMPLE_ROBOT_DATA

TROT: tuple[tuple[str, ...], ...] = (("LF", "RH"), ("RF", "LH"))
"""A quadruped's trot: the diagonal pairs move together, {LF, RH} touching down at t = 0."""


def _legs(prefixes: Mapping[str, str], joints: tuple[str, str, str], foot: str
          ) -> tuple[LegSpec, ...]:
    """Leg specs from the URDF's leg prefixes (hexaleg leg name → URDF prefix) and name patterns
    with ``{p}`` for the prefix, e.g. ``("{p}_HAA", "{p}_HFE", "{p}_KFE")`` and ``"{p}_FOOT"``."""
    return tuple(LegSpec(leg, tuple(j.format(p=p) for j in joints), foot.format(p=p))
                 for leg, p in prefixes.items())


_HAA_HFE_KFE = ("{p}_HAA", "{p}_HFE", "{p}_KFE")

def _unitree(name: str, title: str, *, stride: float, notes: str) -> RobotDescription:
    """A Unitree quadruped of example-robot-data: ``<name>_description/urdf/<name>.urdf`` and
    ``srdf/<name>.srdf``, legs ``FL FR RL RR`` with ``*_hip/thigh/calf_joint`` and ``*_foot``,
    the knees sprung, a trot."""
    return RobotDescription(
        name=name, title=title, source=EXAMPLE_ROBOT_DATA,
        urdf=f"{name}_description/urdf/{name}.urdf", srdf=f"{name}_description/srdf/{name}.srdf",
        stand="standing",
        legs=_legs({"LF": "FL", "RF": "FR", "LH": "RL", "RH": "RR"},
                   ("{p}_hip_joint", "{p}_thigh_joint", "{p}_calf_joint"), "{p}_foot"),
        joint_kinds=("hip", "thigh", "knee"), spring_class="knee",
        gait={"period": 0.6, "duty_factor": 0.6, "stride_length": stride,
              "step_height": stride / 2, "groups": TROT},
        notes=notes)


DESCRIPTIONS: Mapping[str, RobotDescription] = MappingProxyType({d.name: d for d in (
    RobotDescription(
        name="hexaleg", title="hexaleg: the switchable hexapod/sphere robot of the paper",
        source=BUILTIN, urdf="hexaleg.urdf", srdf="hexaleg.srdf", stand=STAND,
        legs=HEXALEG_LEGS, joint_kinds=JOINT_KINDS, spring_class="femur",
        notes="urdf/hexaleg.toml (see docs/robot.md); the paper's spring is at the femur joint",
        motor="AX-18A"),
    RobotDescription(
        name="solo12", title="Solo-12 (Open Dynamic Robot Initiative)",
        source=EXAMPLE_ROBOT_DATA, urdf="solo_description/robots/solo12.urdf",
        srdf="solo_description/srdf/solo.srdf", stand="standing",
        legs=_legs({"LF": "FL", "RF": "FR", "LH": "HL", "RH": "HR"}, _HAA_HFE_KFE, "{p}_FOOT"),
        joint_kinds=("haa", "hfe", "kfe"), spring_class="kfe",
        gait={"period": 0.5, "duty_factor": 0.6, "stride_length": 0.08, "step_height": 0.04,
              "groups": TROT},
        notes="example-robot-data solo_description (loader Solo12Loader: robots/solo12.urdf, "
              "srdf/solo.srdf, pose 'standing'); 2.5 kg, thigh and shank 0.16 m",
        motor="ODRI-4004"),
    RobotDescription(
        name="anymal", title="ANYmal B (ANYbotics), example-robot-data's 'anymal'",
        source=EXAMPLE_ROBOT_DATA, urdf="anymal_b_simple_description/robots/anymal.urdf",
        srdf="anymal_b_simple_description/srdf/anymal.srdf", stand="standing",
        legs=_legs({leg: leg for leg in ("LF", "RF", "LH", "RH")}, _HAA_HFE_KFE, "{p}_FOOT"),
        joint_kinds=("haa", "hfe", "kfe"), spring_class="kfe",
        gait={"period": 0.8, "duty_factor": 0.6, "stride_length": 0.2, "step_height": 0.08,
              "groups": TROT},
        notes="example-robot-data anymal_b_simple_description (loader ANYmalLoader); 30.5 kg"),
    RobotDescription(
        name="anymal_c", title="ANYmal C (ANYbotics)",
        source=EXAMPLE_ROBOT_DATA, urdf="anymal_c_simple_description/urdf/anymal.urdf",
        srdf="anymal_c_simple_description/srdf/anymal.srdf", stand="standing",
        legs=_legs({leg: leg for leg in ("LF", "RF", "LH", "RH")}, _HAA_HFE_KFE, "{p}_FOOT"),
        joint_kinds=("haa", "hfe", "kfe"), spring_class="kfe",
        gait={"period": 0.8, "duty_factor": 0.6, "stride_length": 0.2, "step_height": 0.08,
              "groups": TROT},
        notes="example-robot-data anymal_c_simple_description (loader ANYmalCLoader); 52.1 kg"),
    _unitree("go2", "Go2 (Unitree)", stride=0.12,
             notes="example-robot-data go2_description (loader Go2Loader); 16.1 kg; the knee "
                   "class is the URDF's calf joints"),
    dataclasses.replace(_unitree(
        "a1", "A1 (Unitree)", stride=0.12,
        notes="example-robot-data a1_description (loader A1Loader); thigh and calf 0.2 m; its "
              "joints' energy model of published A1 work (A1-Yang2021: P = τ q̇ + 0.3 τ²)"),
        motor="A1-Yang2021"),
)})
"""The registered robots by name; :data:`DEFAULT_ROBOT` first."""

DEFAULT_ROBOT = "hexaleg"
ROBOT_HELP = (f"a registered robot ({', '.join(DESCRIPTIONS)}) or a robot description "
              "FILE.toml of one's own (docs/robots.md)")
"""What a command's ``--robot`` takes (:func:`description`'s names), in every command's help."""


def description(name: str = DEFAULT_ROBOT) -> RobotDescription:
    """The registered description called ``name``, or one read from a TOML file.

    Args:
        name: A key of :data:`DESCRIPTIONS`, or a path ending in ``.toml``
            (:meth:`RobotDescription.from_toml`).

    Returns:
        The description.

    Raises:
        UnknownNameError: no such robot; the message lists the registered names.
        ConfigError: a TOML description cannot be read or is malformed.
    """
    if isinstance(name, str) and name.endswith(".toml"):
        return RobotDescription.from_toml(name)
    if isinstance(name, str) and name.lower().endswith((".urdf", ".xml", ".xacro")):
        raise InvalidParameterError("robot", name, "a registered robot ("
                                    + ", ".join(DESCRIPTIONS) + ") or a description FILE.toml; "
                                    "a URDF is given through one: [robot] name = …, urdf = "
                                    f"{Path(name).name!r} (five lines, docs/robots.md)")
    if not isinstance(name, str) or name not in DESCRIPTIONS:
        raise UnknownNameError("robot", name, DESCRIPTIONS)
    return DESCRIPTIONS[name]


@typed
def load(name: str = DEFAULT_ROBOT) -> Robot:
    """Load a registered robot by name (``"hexaleg"``, ``"solo12"``, ``"anymal"``, …), or one's
    own robot from a TOML description (:meth:`RobotDescription.from_toml`).

    Args:
        name: A key of :data:`DESCRIPTIONS`, or a path ending in ``.toml``.

    Returns:
        The robot, with the standing pose as ``"stand"`` (see :meth:`RobotDescription.load`).

    Raises:
        UnknownNameError: no such robot; the message lists the registered names.
        RobotModelError: the robot's files cannot be found or loaded.
        ConfigError: a TOML description cannot be read or is malformed.
    """
    return description(name).load()
