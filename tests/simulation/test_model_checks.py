"""What MuJoCo would refuse, named before compiling: impossible inertias, the base below feet."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import hexaleg
from hexaleg.errors import RobotModelError
from hexaleg.robot.catalogue import motor
from hexaleg.robot.model import load_robot
from hexaleg.robot.registry import load
from hexaleg.simulation.mjcf import MJ_EPS, check_inertias, check_size
from hexaleg.simulation.model import build_model

DATA = Path(__file__).resolve().parents[1] / "data"
ROOT = '<link name="base_link">'
BELOW = ('<link name="ground_ref"/>\n  <joint name="ground_to_base" type="fixed"><parent '
         'link="ground_ref"/><child link="base_link"/><origin xyz="0 0 0.3"/></joint>\n  ' + ROOT)
"""A root link 0.3 m below the spider's body: the feet (0.1 m below the body at the zero
configuration) are 0.2 m above the root."""


def spider(tmp_path: Path, old: str, new: str, stand: str = "stand = {}") -> Path:
    """spider.urdf/.toml copied to ``tmp_path`` with ``old`` → ``new`` in the URDF and the
    TOML's stand replaced by ``stand``; returns the TOML."""
    text = (DATA / "spider.urdf").read_text()
    assert old in text
    (tmp_path / "spider.urdf").write_text(text.replace(old, new, 1))
    toml = (DATA / "spider.toml").read_text().replace("stand = {body_height = 0.08}", stand)
    (tmp_path / "spider.toml").write_text(toml)
    return tmp_path / "spider.toml"


def test_root_below_the_feet_is_a_named_error_before_building(tmp_path):
    """A description refuses this robot at load (tests/robot/test_root.py); loaded from the URDF
    alone, with no stand to check, the simulation still names it before building."""
    spider(tmp_path, ROOT, BELOW)
    robot = load_robot(tmp_path / "spider.urdf", legs="auto", heading=(0.0, 1.0, 0.0))
    motion = hexaleg.gait(robot, hexaleg.GaitParams(samples=20))
    with pytest.raises(RobotModelError) as info:
        build_model(robot, motion, motor("AX-18A"))
    text = str(info.value)
    assert "-0.2 m above the mean foot" in text and "allowed: > 0 m" in text
    assert "root frame (link ground_ref)" in text


def test_kept_impossible_inertia_is_a_named_error_not_a_mujoco_traceback(tmp_path):
    bad = '<inertia ixx="1e-06" ixy="0" ixz="0" iyy="1e-06" iyz="0" izz="5e-05"/>'
    spider(tmp_path, '<inertia ixx="2.527e-05" ixy="0" ixz="0" iyy="2.527e-05" iyz="0" '
           'izz="5.4e-07"/>', bad)
    robot = load_robot(tmp_path / "spider.urdf", legs="auto", inertias="keep")
    with pytest.raises(RobotModelError) as info:
        check_inertias(robot)
    text = str(info.value)
    assert "link a_shin" in text and "I1 + I2 < I3" in text and f"{MJ_EPS:g} kg·m²" in text
    assert 'inertias="repair"' in text


def test_every_registry_robot_passes_the_mujoco_checks():
    for name in ("hexaleg", "solo12", "anymal"):
        check_inertias(load(name))


THIGH_INERTIA = ('<mass value="0.04"/>\n      <inertia ixx="1.28e-06" ixy="0" ixz="0" '
                 'iyy="2.19733e-05" iyz="0" izz="2.19733e-05"/>')
THIGH_GEOM = ('<collision><origin xyz="0.04 0 0" rpy="0 1.5707963 0"/><geometry><cylinder '
              'radius="0.008" length="0.08"/>')


def mujoco_refuses(body: str) -> bool:
    """Whether MuJoCo's compiler refuses a moving body with this MJCF inside (the reason our
    check exists: each case below is one MuJoCo would stop on)."""
    import mujoco

    try:
        mujoco.MjModel.from_xml_string(f"<mujoco><worldbody><body><freejoint/>{body}</body>"
                                       "</worldbody></mujoco>")
    except ValueError:
        return True
    return False


@pytest.mark.parametrize(("new", "expected", "mjcf"), [
    ('<mass value="0"/>\n      <inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/>',
     "mass 0 kg (allowed: > 1e-15 kg)",
     '<inertial pos="0 0 0" mass="0" diaginertia="0 0 0"/>'),
    ('<mass value="0.04"/>\n      <inertia ixx="-1e-06" ixy="0" ixz="0" iyy="2.19733e-05" '
     'iyz="0" izz="2.19733e-05"/>', "principal moments -1e-06, 2.19733e-05, 2.19733e-05 kg·m² "
     "(allowed: all > 0 kg·m²)",
     '<inertial pos="0 0 0" mass="0.04" fullinertia="-1e-06 2.2e-05 2.2e-05 0 0 0"/>'),
])
def test_each_inertia_mujoco_refuses_is_named_with_its_link(tmp_path, new, expected, mjcf):
    """A zero mass and a negative principal moment on the thigh (kept as written): the error
    names the link and the value, and MuJoCo itself would refuse the same body."""
    spider(tmp_path, THIGH_INERTIA, new)
    robot = load_robot(tmp_path / "spider.urdf", legs="auto", inertias="keep")
    with pytest.raises(RobotModelError) as info:
        check_inertias(robot)
    assert "link a_thigh" in str(info.value) and expected in str(info.value)
    assert mujoco_refuses(mjcf)


def test_a_zero_size_geometry_is_named_before_compiling(tmp_path):
    """A thigh cylinder of radius 0 loaded in Pinocchio and MuJoCo refuses it ("size 0 must be
    positive"): the URDF check names it when the robot loads; a shape of no size made another
    way (a flat mesh's box) is named by check_size before compiling."""
    spider(tmp_path, THIGH_GEOM, THIGH_GEOM.replace('radius="0.008"', 'radius="0"'),
           "stand = {body_height = 0.08}")
    with pytest.raises(RobotModelError, match=r"link 'a_thigh', <cylinder radius=\"0\">: "
                                              r"expected sizes > 0"):
        load(str(tmp_path / "spider.toml"))
    robot = hexaleg.load()
    obj = robot.collision_model.geometryObjects[0]
    with pytest.raises(RobotModelError) as info:
        check_size(robot, obj, "box", np.array([0.01, 0.0, 0.02]))
    text = str(info.value)
    assert f"geometry {obj.name} of link" in text and "box size 0.01 0.0 0.02 m" in text
    assert "allowed: all > 0 m" in text
    assert mujoco_refuses('<inertial pos="0 0 0" mass="1" diaginertia="1 1 1"/>'
                          '<geom type="cylinder" size="0 0.04"/>')
