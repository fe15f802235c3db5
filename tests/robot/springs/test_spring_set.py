"""Tests of hexaleg.robot.springs.spring_set: springs on a robot's joints, by name and column."""


from __future__ import annotations

import numpy as np
import pytest

from hexaleg.errors import ConfigError, InvalidParameterError, UnknownNameError
from hexaleg.robot.model import load_robot
from hexaleg.robot.springs import (
    DeadZoneSpring,
    LinearSpring,
    OneSidedSpring,
    PreloadedSpring,
    SpringSet,
    StiffeningSpring,
)


def test_spring_set_torques_columns(robot):
    femur = DeadZoneSpring(10.0, theta_k=0.1)
    tibia = DeadZoneSpring(4.0, theta_k=0.05, k2=0.5, damping=0.2)
    springs = SpringSet({"LF_femur": femur, "RH_tibia": tibia})
    T = 5
    q = np.tile(robot.pose("stand"), (T, 1))
    q[:, 7:] += np.linspace(0, 0.4, T)[:, None]
    v = np.ones((T, robot.model.nv))
    tau = springs.torques(robot, q, v)
    assert tau.shape == (T, robot.nj)
    cf, ct = robot.column("LF_femur"), robot.column("RH_tibia")
    np.testing.assert_allclose(tau[:, cf], femur.torque(q[:, 7 + cf], v[:, 6 + cf]))
    np.testing.assert_allclose(tau[:, ct], tibia.torque(q[:, 7 + ct], v[:, 6 + ct]))
    others = np.delete(tau, [cf, ct], axis=1)
    assert np.all(others == 0)
    e = springs.energies(robot, q)
    assert e.shape == (T, robot.nj)
    np.testing.assert_allclose(e[:, cf], femur.energy(q[:, 7 + cf]))
    # Empty set and a spring on every joint both work.
    assert np.all(SpringSet().torques(robot, q) == 0)
    full = SpringSet({j: femur for j in robot.joint_names})
    assert full.torques(robot, q).shape == (T, robot.nj)


def test_spring_set_errors(robot):
    q = np.tile(robot.pose("zero"), (2, 1))
    with pytest.raises(UnknownNameError, match="LF_femur") as e:
        SpringSet({"LF_knee": DeadZoneSpring(1.0, theta_k=0.1)}).torques(robot, q)
    assert "LF_knee" in str(e.value)
    with pytest.raises(InvalidParameterError, match=r"q\.shape"):
        SpringSet().torques(robot, q[:, :10])
    bad = q.copy()
    bad[1, 9] = np.nan
    with pytest.raises(InvalidParameterError, match="nan"):
        SpringSet().energies(robot, bad)
    with pytest.raises(InvalidParameterError):
        SpringSet({"LF_femur": 3.0})  # type: ignore[dict-item]


def test_spring_set_from_toml_table():
    s = SpringSet.from_mapping({"LF_femur": {"stiffness": 20, "theta_k": 0.12, "alpha": 1.05}})
    assert s["LF_femur"].stiffness == 20.0 and s["LF_femur"].theta_k == 0.12
    with pytest.raises(UnknownNameError, match="stiffness"):
        SpringSet.from_mapping({"LF_femur": {"stifness": 20}})
    with pytest.raises(ConfigError):
        SpringSet.from_mapping({"LF_femur": {"stiffness": "hard", "theta_k": 0.1}})


def test_spring_on_continuous_joint_uses_its_angle(tmp_path):
    # A continuous joint stores (cos θ, sin θ) in q; the spring must see θ.
    from hexaleg.robot.model import LegSpec

    inertial = ('<inertial><mass value="0.1"/><inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" '
                'iyz="0" izz="1e-4"/></inertial>')
    urdf = tmp_path / "one.urdf"
    urdf.write_text(
        f'<robot name="one"><link name="base">{inertial}</link><link name="arm">{inertial}</link>'
        '<link name="foot"/><joint name="j" type="continuous"><parent link="base"/>'
        '<child link="arm"/><axis xyz="0 0 1"/></joint><joint name="f" type="fixed">'
        '<parent link="arm"/><child link="foot"/><origin xyz="0.1 0 0"/></joint></robot>')
    one = load_robot(urdf, legs=[LegSpec("L", ("j",), "foot")], joint_kinds=("j",))
    assert one.model.nq == 9 and one.nj == 1
    theta = np.array([0.05, 0.5, -0.7])
    q = np.zeros((3, 9))
    q[:, 6] = 1.0  # identity base quaternion
    q[:, 7], q[:, 8] = np.cos(theta), np.sin(theta)
    s = DeadZoneSpring(2.0, theta_k=0.1)
    springs = SpringSet({"j": s})
    np.testing.assert_allclose(springs.torques(one, q)[:, 0], s.torque(theta))
    np.testing.assert_allclose(springs.energies(one, q)[:, 0], s.energy(theta))


def test_any_family_and_a_named_error_where_a_dead_zone_is_needed(robot):
    s = SpringSet({"LF_femur": LinearSpring(0.5, 0.4, 0.1),
                   "LF_tibia": DeadZoneSpring(1.0, theta_k=0.1)})
    q = np.tile(robot.pose("stand"), (3, 1))
    tau = s.torques(robot, q)
    c = robot.column("LF_femur")
    assert tau[0, c] == pytest.approx(0.1 - 0.5 * (q[0, 7 + c] - 0.4))
    with pytest.raises(InvalidParameterError, match=r"LF_femur.*LinearSpring"):
        s.dead_zones("a stiffness curve")
    with pytest.raises(InvalidParameterError, match="spring law"):
        SpringSet({"LF_femur": 1.0})


def test_springs_must_be_a_mapping_and_a_dead_zone_must_be_able_to_engage(robot):
    spring = DeadZoneSpring(stiffness=1.0, theta_k=0.1)
    with pytest.raises(InvalidParameterError, match=r"invalid springs = \[DeadZoneSpring.*a "
                                                    r"mapping joint name → spring"):
        SpringSet([spring])  # type: ignore[arg-type]
    q = np.tile(robot.pose("stand"), (3, 1))
    wide = SpringSet({"LF_femur": DeadZoneSpring(stiffness=1.0, theta_k=6.0)})
    with pytest.raises(InvalidParameterError, match=r"dead zone of the spring on LF_femur = "
                                                    r"'\[-6, 6\] rad'.*\[-2\.618, 2\.618\] rad "
                                                    r"\(URDF limits\).*never engage"):
        wide.torques(robot, q)
    # a dead zone that ends inside the range on one side may engage: accepted
    one_side = DeadZoneSpring(stiffness=1.0, theta_k=2.0, neutral=1.0)
    assert SpringSet({"LF_femur": one_side}).torques(robot, q).shape == (3, robot.nj)


@pytest.mark.parametrize(("spring", "says"), [
    (OneSidedSpring(stiffness=0.5, contact=90.0), r"k acts above 90 rad"),
    (OneSidedSpring(stiffness=0.5, contact=-3.0, side="below", preload=0.1),
     r"k acts below -3 rad, preload acts below -3 rad"),
    (PreloadedSpring(stiffness=0.5, preload=0.1, theta_k=3.0),
     r"k_plus acts above 3 rad, k_minus acts below -3 rad, preload_plus acts above 3 rad, "
     r"preload_minus acts below -3 rad"),
    (StiffeningSpring(above=((2.7, 1.0), (3.0, 2.0))),
     r"k_above_1 acts above 2\.7 rad, k_above_2 acts above 3 rad")])
def test_every_family_must_be_able_to_engage(robot, spring, says):
    """The rule a dead zone had, for every family: a one-sided contact outside the femur's
    ±2.618 rad (degrees written as radians) used to be accepted and save a silent 0 %."""
    with pytest.raises(InvalidParameterError, match=rf"on LF_femur = '{says}'; allowed: a spring "
                                                    r"that engages inside the joint's range "
                                                    r"\[-2\.618, 2\.618\] rad"):
        SpringSet({"LF_femur": spring}).columns(robot)


def test_springs_that_engage_somewhere_in_the_range_are_accepted(robot):
    ok = {"LF_femur": OneSidedSpring(stiffness=0.5, contact=2.5),
          "LF_tibia": OneSidedSpring(stiffness=0.5, contact=-2.5, side="below"),
          "LF_coxa": StiffeningSpring(above=((2.5, 1.0), (3.0, 2.0))),
          "RF_femur": PreloadedSpring(stiffness=0.5, preload=0.0, theta_plus=3.0,
                                      theta_minus=-1.0),
          "RF_tibia": OneSidedSpring(stiffness=0.0, contact=90.0),  # no magnitude: no spring
          # a design's group whose dead zone holds the whole range: zero stiffness, no spring
          "LM_femur": DeadZoneSpring(stiffness=0.0, stiffness_minus=0.0, theta_k=6.0)}
    assert len(SpringSet(ok).columns(robot)) == 6
